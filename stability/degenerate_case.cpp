// Axis-aligned and degenerate rays: zero direction components on one and two axes, origins exactly
// on the scene box's faces or on split planes of the built structures (kd-tree splits, BVH node
// faces, grid cell walls), denormal direction components: each structure (robust and plain) must
// give the same closest hit as a box-free loop over every triangle (watertight method, float).
// Invalid rays (zero or denormal-only direction, NaN or inf anywhere, tmin > tmax) must be rejected
// before any node is visited (TraversalStats::nodes stays 0) and never hit.
// Scene: the intgrid mesh at SF 2 (closed cube [-2, 2]^3, 192 triangles).
#include "accel/any_accel.h"
#include "datasets_gen/generators.h"
#include "intersect/triangle/watertight.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "trace/clip.h"
#include "trace/scene_tracer.h"

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <tbb/global_control.h>

namespace rtlab::stab {

namespace {

constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();
constexpr float inf_f = std::numeric_limits<float>::infinity();
constexpr float denorm_f = 1e-40f;  // a float denormal (FLT_MIN is about 1.18e-38)

/// Split planes of the structures built over `bounds`: per axis, every kd-tree split, BVH node
/// face and grid cell wall inside the scene box.
std::array<std::vector<float>, 3> split_planes(const std::vector<Bounds3f>& bounds,
                                               const ClipFn& clip) {
    std::array<std::vector<float>, 3> planes;
    for (const AccelEntry& e : accel_registry()) {
        const AnyAccel a = build_accel(default_spec(e), BuildInput{bounds, clip});
        if (const auto* kd = std::get_if<KdTree>(&a)) {
            for (const KdNode& n : kd->nodes) {
                if (!n.is_leaf()) {
                    planes[n.axis()].push_back(n.split());
                }
            }
        } else if (const auto* bvh = std::get_if<Bvh>(&a)) {
            for (const BvhNode& n : bvh->nodes) {
                for (std::size_t k = 0; k < 3; ++k) {
                    planes[k].push_back(n.lo[k]);
                    planes[k].push_back(n.hi[k]);
                }
            }
        } else if (const auto* grid = std::get_if<Grid>(&a)) {
            for (std::size_t k = 0; k < 3; ++k) {
                for (std::uint32_t i = 0; i <= grid->res[k]; ++i) {
                    planes[k].push_back(grid->box.lo[k] +
                                        static_cast<float>(i) * grid->cell_size[k]);
                }
            }
        }
    }
    for (auto& p : planes) {
        std::sort(p.begin(), p.end());
        p.erase(std::unique(p.begin(), p.end()), p.end());
    }
    return planes;
}

/// A named set of valid rays.
struct RaySet {
    std::string name;
    std::vector<Rayf> rays;
};

/// The valid degenerate ray sets for the cube [-h, h]^3.
std::vector<RaySet> valid_sets(float h,
                               const std::array<std::vector<float>, 3>& planes,
                               std::size_t n,
                               std::uint64_t seed) {
    Sampler rng(seed, 303);
    const auto inside = [&] {
        return Vec3f(Vec3d{rng.uniform(-h, h), rng.uniform(-h, h), rng.uniform(-h, h)} * 0.95);
    };
    const auto signed_zero = [&] { return rng.index(2) == 0 ? 0.0f : -0.0f; };
    std::vector<RaySet> sets{{"one zero direction component", {}},
                             {"two zero direction components", {}},
                             {"origin on a scene-box face", {}},
                             {"origin on a split plane", {}},
                             {"denormal direction components", {}}};
    for (std::size_t i = 0; i < n; ++i) {
        Rayf r;
        const std::size_t a = rng.index(3);
        r.org = inside();
        r.dir = Vec3f(rng.unit());
        r.dir[a] = signed_zero();
        sets[0].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f{signed_zero(), signed_zero(), signed_zero()};
        r.dir[a] = (rng.index(2) == 0 ? 1.0f : -1.0f) * static_cast<float>(rng.uniform(0.25, 4));
        sets[1].rays.push_back(r);

        r.org = inside();
        r.org[a] = rng.index(2) == 0 ? h : -h;
        r.dir = Vec3f(rng.unit());
        if (i % 3 == 0) {
            r.dir[a] = signed_zero();  // in the face plane
        }
        sets[2].rays.push_back(r);

        r.org = inside();
        const std::vector<float>& p = planes[a];
        if (!p.empty()) {
            r.org[a] = p[rng.index(p.size())];
        }
        r.dir = Vec3f(rng.unit());
        if (i % 2 == 0) {
            r.dir[a] = signed_zero();  // lying in the split plane
        }
        sets[3].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f(rng.unit());
        r.dir[a] = (rng.index(2) == 0 ? 1.0f : -1.0f) * denorm_f;
        if (i % 2 == 0) {
            const std::size_t b = (a + 1) % 3;
            r.dir[b] =
                (rng.index(2) == 0 ? 1.0f : -1.0f) * std::numeric_limits<float>::denorm_min();
        }
        sets[4].rays.push_back(r);
    }
    return sets;
}

/// The invalid ray sets: every ray must be rejected without a traversal.
std::vector<RaySet> invalid_sets(float h, std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 404);
    const auto inside = [&] {
        return Vec3f(Vec3d{rng.uniform(-h, h), rng.uniform(-h, h), rng.uniform(-h, h)} * 0.95);
    };
    std::vector<RaySet> sets{{"rejected: zero direction", {}},
                             {"rejected: denormal-only direction", {}},
                             {"rejected: NaN in origin or direction", {}},
                             {"rejected: inf in origin or direction", {}},
                             {"rejected: NaN window or tmin > tmax", {}}};
    for (std::size_t i = 0; i < n; ++i) {
        Rayf r;
        r.org = inside();
        r.dir = Vec3f{0, 0, 0};
        if (i % 2 == 1) {
            r.dir = Vec3f{-0.0f, 0.0f, -0.0f};
        }
        sets[0].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f{denorm_f, -denorm_f, std::numeric_limits<float>::denorm_min()};
        sets[1].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f(rng.unit());
        (i % 2 == 0 ? r.org : r.dir)[rng.index(3)] = nan_f;
        sets[2].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f(rng.unit());
        (i % 2 == 0 ? r.org : r.dir)[rng.index(3)] = rng.index(2) == 0 ? inf_f : -inf_f;
        sets[3].rays.push_back(r);

        r.org = inside();
        r.dir = Vec3f(rng.unit());
        switch (i % 3) {
        case 0:
            r.tmin = nan_f;
            break;
        case 1:
            r.tmax = nan_f;
            break;
        default:
            r.tmin = 2.0f;
            r.tmax = 1.0f;
        }
        sets[4].rays.push_back(r);
    }
    return sets;
}

/// Closest hit of every ray by testing every triangle (no boxes, no structure).
std::vector<Hit> reference_hits(const std::vector<Watertight<float>::Prepared>& tris,
                                const std::vector<Rayf>& rays) {
    std::vector<Hit> out(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        Rayf r = rays[i];
        for (std::uint32_t k = 0; k < tris.size(); ++k) {
            if (const auto h = Watertight<float>::intersect(tris[k], r)) {
                r.tmax = h->t;
                out[i] = {h->t, h->u, h->v, k};
            }
        }
    }
    return out;
}

/// f(name, tracer) for every structure `sel` selects with robust or plain traversal, built on
/// scene with the watertight method.
template <class F>
void for_each_tracer(const Scene& scene, bool robust, const Selection& sel, F&& f) {
    for (const AccelEntry& e : accel_registry()) {
        if (!selected(sel, e.name, robust)) {
            continue;
        }
        TraceSetup setup;
        setup.accel = default_spec(e);
        setup.methods = {"watertight"};
        setup.robust = robust;
        const SceneTracer tracer(scene, setup);
        f(e.name, tracer);
    }
}

/// One valid ray set through every selected structure (watertight method, robust or plain
/// traversal) against the box-free loop's hits `ref`: disagreements, naming the structures.
Row valid_set_row(const Scene& scene,
                  const RaySet& set,
                  const std::vector<Hit>& ref,
                  bool robust,
                  const Selection& sel) {
    std::size_t ref_misses = 0;
    for (const Hit& hit : ref) {
        ref_misses += hit.valid() ? 0 : 1;
    }
    std::size_t failures = 0, rays = 0;
    double ns = 0;
    std::string who;
    for_each_tracer(scene, robust, sel, [&](std::string_view name, const SceneTracer& tracer) {
        const Stopwatch sw;
        const std::vector<Hit> hits = trace_all(tracer, set.rays, false);
        ns += sw.ns();
        std::size_t f = 0;
        for (std::size_t i = 0; i < hits.size(); ++i) {
            const Hit& a = hits[i];
            const Hit& b = ref[i];
            f += a.valid() != b.valid() || (a.valid() && a.t != b.t) ? 1 : 0;
        }
        failures += f;
        rays += hits.size();
        if (f > 0) {
            who += (who.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(f);
        }
    });
    std::string note = "all structures vs a box-free loop";
    if (!who.empty()) {
        note += "; disagreeing: " + who;
    }
    if (ref_misses > 0) {
        note += "; the box-free loop itself misses " + std::to_string(ref_misses);
    }
    return make_row("degenerate", set.name + ", watertight " + robust_label(robust), "float", rays,
                    failures, "disagreements", ns / static_cast<double>(rays), note);
}

/// One invalid ray set through every selected structure, robust and plain, closest and any hit,
/// one ray at a time so a single traversal shows in the node count: none may hit or visit a node.
Row invalid_set_row(const Scene& scene, const RaySet& set, const Selection& sel) {
    std::size_t failures = 0, rays = 0;
    std::uint64_t nodes = 0, started = 0;
    for (const bool robust : {false, true}) {
        for_each_tracer(scene, robust, sel, [&](std::string_view, const SceneTracer& tracer) {
            for (const Rayf& r : set.rays) {
                TraversalStats st;
                const std::vector<Rayf> one{r};
                const std::vector<Hit> hit = trace_all(tracer, one, false, &st);
                TraversalStats st_any;
                const std::vector<Hit> blocked = trace_all(tracer, one, true, &st_any);
                const bool bad =
                    hit[0].valid() || blocked[0].valid() || st.nodes > 0 || st_any.nodes > 0;
                failures += bad ? 1 : 0;
                nodes += st.nodes + st_any.nodes;
                started += st.rays + st_any.rays;
                ++rays;
            }
        });
    }
    return make_row("degenerate", set.name, "float", rays, failures, "traversed or hit",
                    std::numeric_limits<double>::quiet_NaN(),
                    "every structure, robust and plain, closest and any hit; nodes visited " +
                        std::to_string(nodes) + ", traversals started " + std::to_string(started));
}

}  // namespace

std::vector<Row> run_degenerate(const Options& opt) {
    return run_degenerate(opt, Selection{});
}

std::vector<Row> run_degenerate(const Options& opt, const Selection& sel) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    gen::GenOptions g;
    g.size = 2;
    const Scene scene = gen::generate("intgrid", g);
    const TriangleMesh& mesh = scene.meshes[0].mesh;
    const float h = mesh.bounds().hi.x;
    std::vector<Watertight<float>::Prepared> tris;
    std::vector<Bounds3f> bounds;
    for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
        const auto c = mesh.corners(i);
        tris.push_back(Watertight<float>::prepare({c[0], c[1], c[2]}));
        bounds.push_back(mesh.triangle_bounds(i));
    }
    const ClipFn clip = [&mesh](std::uint32_t i, const Bounds3f& box) {
        const auto c = mesh.corners(i);
        return clip_triangle_bounds(c[0], c[1], c[2], box);
    };
    const std::size_t per_set = std::max<std::size_t>(opt.rays / 5, 1);
    const std::vector<RaySet> valid = valid_sets(h, split_planes(bounds, clip), per_set, opt.seed);
    const std::vector<RaySet> invalid =
        invalid_sets(h, std::max<std::size_t>(per_set / 10, 10), opt.seed);
    std::vector<std::vector<Hit>> refs;
    for (const RaySet& s : valid) {
        refs.push_back(reference_hits(tris, s.rays));
    }

    std::vector<Row> rows;
    for (std::size_t s = 0; s < valid.size(); ++s) {
        for (const bool robust : {false, true}) {
            if (robust ? sel.robust : sel.plain) {
                rows.push_back(valid_set_row(scene, valid[s], refs[s], robust, sel));
            }
        }
    }
    for (const RaySet& s : invalid) {
        rows.push_back(invalid_set_row(scene, s, sel));
    }
    return rows;
}

}  // namespace rtlab::stab
