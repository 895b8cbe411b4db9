// Structures: every structure of the registry, robust and plain, against a box-free loop over every
// primitive with the same method (a disagreement in hit/miss, or a t more than 1e-4 relative away,
// is a failure; closer t are coplanar ties and only reported), on four scenes: a constructed "hit
// beyond the first cell or leaf" scene (a long slanted triangle whose box fills the first cells and
// leaves, hit far away, in front of which a small square is hit first; six orientations), the
// `stadium` and `scales` stress scenes, and axis-aligned squares on integer planes (primitives
// exactly on split planes).
#include "datasets_gen/generators.h"
#include "intersect/sphere/stable.h"
#include "intersect/triangle/watertight.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "trace/ray_gen.h"
#include "trace/scene_tracer.h"

#include <cmath>
#include <string>
#include <tbb/global_control.h>
#include <utility>

namespace rtlab::stab {

namespace {

/// A scene with its rays and the box-free reference hits.
struct Workload {
    std::string name;
    Scene scene;
    std::vector<Rayf> rays;
    std::vector<Hit> reference;
    std::string method;  ///< the method every structure uses
};

/// Every triangle of every mesh, prepared for the watertight method, in global id order.
std::vector<Watertight<float>::Prepared> scene_triangles(const Scene& s) {
    std::vector<Watertight<float>::Prepared> out;
    for (const MeshObject& m : s.meshes) {
        for (std::size_t i = 0; i < m.mesh.triangle_count(); ++i) {
            const auto c = m.mesh.corners(i);
            out.push_back(Watertight<float>::prepare({c[0], c[1], c[2]}));
        }
    }
    return out;
}

/// Closest hits by testing every primitive with method M (no boxes).
template <class M>
std::vector<Hit> box_free(const std::vector<typename M::Prepared>& prims,
                          const std::vector<Rayf>& rays) {
    std::vector<Hit> out(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        Rayf r = rays[i];
        if (!is_valid(r)) {
            continue;
        }
        for (std::uint32_t k = 0; k < prims.size(); ++k) {
            if (const auto h = M::intersect(prims[k], r)) {
                r.tmax = h->t;
                out[i] = {h->t, h->u, h->v, k};
            }
        }
    }
    return out;
}

/// Maps the construction frame (rays along +x) to axis a with sign s.
Vec3f orient(const Vec3f& p, std::size_t a, float s) {
    Vec3f q;
    q[a] = s * p.x;
    q[(a + 1) % 3] = p.y;
    q[(a + 2) % 3] = p.z;
    return q;
}

void push_tri(TriangleMesh& m, const Vec3f& a, const Vec3f& b, const Vec3f& c) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.triangles.push_back({base, base + 1, base + 2});
}

/// The "beyond the first cell" construction in orientation (a, s), rays from x = -1 towards +x.
Workload beyond_cell(std::size_t a, float s, std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 500 + a * 2 + (s > 0 ? 1 : 0));
    TriangleMesh m;
    const auto o = [&](float x, float y, float z) { return orient({x, y, z}, a, s); };
    // P1: plane z = (x - 10) / 8, narrowing from y in [-2, 2] at x = 0 to a point at x = 16.
    push_tri(m, o(0, -2, -1.25f), o(0, 2, -1.25f), o(16, 0, 0.75f));
    // P2: the square x = 6, |y|, |z| <= 0.5, hit before P1 but met after it.
    push_tri(m, o(6, -0.5f, -0.5f), o(6, 0.5f, -0.5f), o(6, 0.5f, 0.5f));
    push_tri(m, o(6, -0.5f, -0.5f), o(6, 0.5f, 0.5f), o(6, -0.5f, 0.5f));
    // P3: behind P1's hit, must lose to it.
    push_tri(m, o(12, 0.4f, -1), o(12, 0.9f, -1), o(12, 0.65f, 1));
    // Filler away from the corridor |y|, |z| < 1.5, so cells and leaves get small.
    for (int i = 0; i < 600; ++i) {
        const Vec3f c{static_cast<float>(rng.uniform(0, 16)),
                      static_cast<float>(rng.uniform(1.6, 8) * (rng.index(2) ? 1 : -1)),
                      static_cast<float>(rng.uniform(-8, 8))};
        const Vec3f c2 = i % 2 ? Vec3f{c.x, c.z, c.y} : c;
        push_tri(m, o(c2.x, c2.y, c2.z), o(c2.x + 0.2f, c2.y, c2.z),
                 o(c2.x, c2.y + 0.2f, c2.z + 0.1f));
    }
    Workload w;
    w.name = "beyond first cell/leaf, rays along " + std::string(s > 0 ? "+" : "-") +
             std::string(1, static_cast<char>('x' + a));
    w.method = "watertight";
    w.scene = mesh_scene(std::move(m));
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3f org{-1, static_cast<float>(rng.uniform(-0.45, 0.85)),
                        static_cast<float>(rng.uniform(-0.45, 0.45))};
        const Vec3f dir{1, static_cast<float>(rng.uniform(-1e-3, 1e-3)),
                        static_cast<float>(rng.uniform(-1e-3, 1e-3))};
        w.rays.push_back({o(org.x, org.y, org.z), o(dir.x, dir.y, dir.z)});
    }
    w.reference = box_free<Watertight<float>>(scene_triangles(w.scene), w.rays);
    return w;
}

/// Axis-aligned squares with integer corners in [0, 8]^3: faces lie exactly on split planes.
Workload split_plane_squares(std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 510);
    TriangleMesh m;
    for (int i = 0; i < 300; ++i) {
        const std::size_t a = rng.index(3);
        Vec3f lo{static_cast<float>(rng.index(8)), static_cast<float>(rng.index(8)),
                 static_cast<float>(rng.index(8))};
        lo[a] = static_cast<float>(rng.index(9));
        const float w1 = static_cast<float>(1 + rng.index(3));
        const float w2 = static_cast<float>(1 + rng.index(3));
        Vec3f e1, e2;
        e1[(a + 1) % 3] = w1;
        e2[(a + 2) % 3] = w2;
        push_tri(m, lo, lo + e1, lo + e1 + e2);
        push_tri(m, lo, lo + e1 + e2, lo + e2);
    }
    Workload w;
    w.name = "squares on integer split planes";
    w.method = "watertight";
    w.scene = mesh_scene(std::move(m));
    for (std::size_t i = 0; i < n; ++i) {
        Rayf r;
        r.org = Vec3f(Vec3d{rng.uniform(-1, 9), rng.uniform(-1, 9), rng.uniform(-1, 9)});
        if (i % 2 == 0) {
            // Axis-aligned, in integer planes on one or both transverse axes.
            const std::size_t a = rng.index(3);
            r.org[(a + 1) % 3] = static_cast<float>(rng.index(9));
            if (i % 4 == 0) {
                r.org[(a + 2) % 3] = static_cast<float>(rng.index(9));
            }
            r.dir[a] = rng.index(2) ? 1.0f : -1.0f;
        } else {
            r.dir = Vec3f(rng.unit());
        }
        w.rays.push_back(r);
    }
    w.reference = box_free<Watertight<float>>(scene_triangles(w.scene), w.rays);
    return w;
}

/// The generated scene `scene` at size 3 with n / 2 of its primary rays, the rest of the rays and
/// the reference left to the caller.
Workload generated_workload(
    const char* scene, std::string name, std::string method, std::size_t n, std::uint64_t seed) {
    gen::GenOptions g;
    g.size = 3;
    Workload w;
    w.name = std::move(name);
    w.method = std::move(method);
    w.scene = gen::generate(scene, g);
    w.rays = make_rays(w.scene, RayKind::primary, n / 2, seed);
    return w;
}

Workload stadium(std::size_t n, std::uint64_t seed) {
    Workload w = generated_workload("stadium", "stadium (SF 3), primary + random rays",
                                    "watertight", n, seed);
    const std::vector<Rayf> more = make_rays(w.scene, RayKind::random, n - n / 2, seed);
    w.rays.insert(w.rays.end(), more.begin(), more.end());
    w.reference = box_free<Watertight<float>>(scene_triangles(w.scene), w.rays);
    return w;
}

Workload scales(std::size_t n, std::uint64_t seed) {
    Workload w = generated_workload(
        "scales", "scales (SF 3, radii 1e-6..1e6), primary + aimed rays", "stable", n, seed);
    Sampler rng(seed, 520);
    const auto& sp = w.scene.spheres;
    for (std::size_t i = w.rays.size(); i < n; ++i) {
        // From 2..100 radii away towards a random point within 0.99 r of a random centre.
        const SphereObject& s = sp[rng.index(sp.size())];
        const Vec3d c(s.center);
        const double r = s.radius;
        const Vec3d org = c + rng.unit() * (r * rng.uniform(2, 100));
        const Vec3d aim = c + rng.ball(0.99 * r);
        w.rays.push_back({Vec3f(org), Vec3f(aim - org)});
    }
    std::vector<SphereStable<float>::Prepared> prims;
    for (const SphereObject& s : sp) {
        prims.push_back(SphereStable<float>::prepare({s.center, s.radius}));
    }
    w.reference = box_free<SphereStable<float>>(prims, w.rays);
    return w;
}

/// A structure's answers against the box-free reference: misses, false hits, and hits whose t
/// differs (with the relative t differences).
struct Tally {
    std::size_t rays = 0, misses = 0, false_hits = 0, t_differs = 0, t_far = 0;
    double ns = 0;
    std::vector<std::pair<double, double>> ts;  ///< (structure t, reference t) of common hits

    void add(const Hit& x, const Hit& ref) {
        ++rays;
        if (x.valid() != ref.valid()) {
            (x.valid() ? false_hits : misses) += 1;
        } else if (x.valid()) {
            t_differs += x.t != ref.t ? 1 : 0;
            // Beyond 1e-4 relative it is another surface; below, a tie of coplanar triangles
            // whose t differ by the method's rounding (either answer is as right).
            t_far += std::abs(x.t - ref.t) > 1e-4f * std::abs(ref.t) ? 1 : 0;
            ts.emplace_back(static_cast<double>(x.t), static_cast<double>(ref.t));
        }
    }
    void merge(const Tally& o) {
        rays += o.rays;
        misses += o.misses;
        false_hits += o.false_hits;
        t_differs += o.t_differs;
        t_far += o.t_far;
        ns += o.ns;
        ts.insert(ts.end(), o.ts.begin(), o.ts.end());
    }
    Row row(const std::string& case_name, const std::string& subject, bool robust) const {
        std::string note;
        if (misses + false_hits + t_differs > 0) {
            note = std::to_string(misses) + " misses, " + std::to_string(false_hits) +
                   " false hits, " + std::to_string(t_far) + " hits on another surface; " +
                   std::to_string(t_differs - t_far) +
                   " coplanar ties at a t within 1e-4 (not failures: overlapping coplanar "
                   "triangles' t differ by rounding, and a node whose entry rounds above the t "
                   "already found is culled" +
                   (robust ? ")" : "; plain traversal culls more)");
        }
        Row r = make_row(case_name, subject, "float", rays, misses + false_hits + t_far,
                         "disagreements", ns / static_cast<double>(std::max<std::size_t>(rays, 1)),
                         note);
        ErrorStats err;
        for (const auto& [t, ref] : ts) {
            err.add(t, ref);
        }
        err.fill(r);
        return r;
    }
};

}  // namespace

std::vector<Row> run_structures(const Options& opt) {
    return run_structures(opt, Selection{});
}

std::vector<Row> run_structures(const Options& opt, const Selection& sel) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    // Each of the four scenes gets opt.rays (a quarter with split_rays); the constructed one
    // shares its rays among six orientations.
    const std::size_t n = std::max<std::size_t>(sel.split_rays ? opt.rays / 4 : opt.rays, 6);
    std::vector<Workload> loads;
    for (std::size_t a = 0; a < 3; ++a) {
        for (const float s : {1.0f, -1.0f}) {
            loads.push_back(beyond_cell(a, s, n / 6, opt.seed));
        }
    }
    loads.push_back(split_plane_squares(n, opt.seed));
    loads.push_back(stadium(n, opt.seed));
    loads.push_back(scales(n, opt.seed));

    std::vector<Row> rows;
    for (const bool robust : {false, true}) {
        for (const AccelEntry& e : accel_registry()) {
            if (!selected(sel, e.name, robust)) {
                continue;
            }
            // The six orientations of the constructed case make one row per structure.
            Tally beyond;
            for (const Workload& w : loads) {
                TraceSetup setup;
                setup.accel = default_spec(e);
                setup.methods = {w.method};
                setup.robust = robust;
                const SceneTracer tracer(w.scene, setup);
                const Stopwatch sw;
                const std::vector<Hit> hits = trace_all(tracer, w.rays, false);
                const double ns = sw.ns();
                Tally tally;
                tally.ns = ns;
                for (std::size_t i = 0; i < hits.size(); ++i) {
                    tally.add(hits[i], w.reference[i]);
                }
                if (w.name.rfind("beyond", 0) == 0) {
                    beyond.merge(tally);
                    continue;
                }
                rows.push_back(tally.row(
                    w.name, std::string(e.name) + " " + robust_label(robust) + ", " + w.method,
                    robust));
            }
            rows.push_back(beyond.row(
                "beyond first cell/leaf (6 orientations)",
                std::string(e.name) + " " + robust_label(robust) + ", watertight", robust));
        }
    }
    // Group rows by scene for the report: stable sort on the case name.
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& x, const Row& y) { return x.case_name < y.case_name; });
    return rows;
}

}  // namespace rtlab::stab
