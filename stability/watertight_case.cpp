// Watertightness (pbrt's "Triangle, Watertight" idea, the stability suite's first case): rays from
// inside a closed, vertex-perturbed sphere mesh, in random directions and aimed exactly at vertices
// and shared edges, must all hit. Every triangle method x every structure x robust on/off, float,
// and every structure in exact mode (whose hits must also equal exact brute force's), traced
// through SceneTracer (the path `rtlab trace` takes); a ray that hits nothing is a leak.
#include "intersect/triangle/methods.h"
#include "intersect/triangle/sphere_mesh.h"
#include "scene/scene_io.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "stability/leak_tally.h"
#include "trace/scene_tracer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <tbb/global_control.h>

namespace rtlab::stab {

TriangleMesh watertight_sphere(std::uint64_t seed) {
    const IndexedMesh m = perturbed_sphere_mesh(seed, 16, 24, 0.1);
    TriangleMesh out;
    out.positions = m.vertices;
    out.triangles = m.faces;
    return out;
}

Scene mesh_scene(TriangleMesh mesh) {
    Scene s;
    s.materials.push_back(Material{});
    s.camera = camera_framing(mesh.bounds());
    MeshObject o;
    o.mesh = std::move(mesh);
    s.add(std::move(o));
    return s;
}

std::vector<Rayf> inside_rays(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
    Sampler rng(seed, 101);
    std::vector<Rayf> rays;
    rays.reserve(count);
    const Vec3f centre{0, 0, 0};  // the sphere's centre, exactly
    for (std::size_t i = 0; i < count; ++i) {
        Rayf r;
        const Vec3f org = centre + Vec3f(rng.ball(0.5));
        switch (i % 3) {
        case 0:
            r.org = org;
            r.dir = Vec3f(rng.unit());
            break;
        case 1: {
            const Vec3f v = mesh.positions[rng.index(mesh.positions.size())];
            if (i % 2 == 0) {
                // From the centre, exactly through v: the scale by 2^k is exact in float.
                r.org = centre;
                r.dir = (v - centre) * std::ldexp(1.0f, static_cast<int>(rng.index(5)) - 2);
            } else {
                r.org = org;
                r.dir = v - org;
            }
            break;
        }
        default: {
            const auto& f = mesh.triangles[rng.index(mesh.triangles.size())];
            const std::size_t e = rng.index(3);
            const Vec3f a = mesh.positions[f[e]];
            const Vec3f b = mesh.positions[f[(e + 1) % 3]];
            const Vec3f target = a + (b - a) * static_cast<float>(rng.uniform(0, 1));
            r.org = i % 2 == 0 ? centre : org;
            r.dir = target - r.org;
            break;
        }
        }
        rays.push_back(r);
    }
    return rays;
}

std::vector<std::string> leak_case_specs() {
    std::vector<std::string> out;
    for (const AccelEntry& e : accel_registry()) {
        out.emplace_back(e.name);
    }
    out.insert(out.end(), accel_variants().begin(), accel_variants().end());
    return out;
}

bool selected(const Selection& sel, std::string_view accel, bool robust) {
    return (robust ? sel.robust : sel.plain) && (sel.brute || accel != "brute");
}

bool selected_method(const Selection& sel, std::string_view method) {
    return sel.methods.empty() ||
           std::find(sel.methods.begin(), sel.methods.end(), method) != sel.methods.end();
}

std::vector<Row> run_watertight(const Options& opt) {
    return run_watertight(opt, Selection{});
}

namespace {

/// The name of exact mode's subjects in the leak cases.
constexpr std::string_view exact_subject = "exact";

/// One subject of a leak case: a triangle method, or exact mode, through one structure.
struct Subject {
    std::string_view method;  ///< a triangle method's name, or exact_subject
    bool robust = false;
    bool any = false;
    std::string spec;
    std::size_t rays = 0;
    double ns = 0;
    LeakTally tally;
    std::size_t disagree = 0;  ///< exact mode: hits other than exact brute force's
};

/// The tracer of sub's spec over scene: sub's method, or exact mode.
SceneTracer subject_tracer(const Scene& scene, const Subject& sub, const std::string& spec) {
    TraceSetup setup;
    setup.accel = parse_accel_spec(spec);
    setup.robust = sub.robust;
    if (sub.method == exact_subject) {
        setup.exact = true;
    } else {
        setup.methods = {std::string(sub.method)};
    }
    return SceneTracer(scene, setup);
}

/// Exact brute force's hits for one scene's rays, kept while the next subject traces the same
/// rays (the leak cases whose rays do not depend on the structure).
struct ExactReference {
    std::size_t scene = ~std::size_t{0};
    std::vector<Rayf> rays;
    std::vector<Hit> hits;

    const std::vector<Hit>& of(const Scene& s, std::size_t k, const std::vector<Rayf>& r) {
        const bool same = k == scene && r.size() == rays.size() &&
                          std::memcmp(r.data(), rays.data(), r.size() * sizeof(Rayf)) == 0;
        if (!same) {
            const Subject brute{exact_subject, true, false, "brute", 0, 0, {}, 0};
            hits = trace_all(subject_tracer(s, brute, "brute"), r, false);
            scene = k;
            rays = r;
        }
        return hits;
    }
};

/// Adds the leaks among hits to sub's tally, classified with sub's method alone (exact mode's
/// with the watertight test's); for exact mode also the rays whose hit differs from exact brute
/// force's (primitive, or t).
void tally_subject(Subject& sub,
                   const Scene& scene,
                   std::size_t k,
                   const std::vector<Rayf>& rays,
                   const std::vector<Hit>& hits,
                   ExactReference& ref) {
    const TriangleMesh& mesh = scene.meshes[0].mesh;
    bool tallied = false;
    for_each_type<TriangleMethods<float>>([&]<class M>() {
        if (M::name == sub.method) {
            tally_leaks<M>(mesh, rays, hits, sub.tally);
            tallied = true;
        }
    });
    if (tallied) {
        return;
    }
    tally_leaks<Watertight<float>>(mesh, rays, hits, sub.tally);
    const std::vector<Hit>& want = ref.of(scene, k, rays);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        sub.disagree += hits[i].prim != want[i].prim || hits[i].t != want[i].t ? 1 : 0;
    }
}

/// Every selected (method, traversal, spec) subject, then exact mode's per spec.
std::vector<Subject> leak_subjects(const std::vector<std::string>& specs, const Selection& sel) {
    std::vector<Subject> subjects;
    for_each_type<TriangleMethods<float>>([&]<class M>() {
        for (const bool robust : {false, true}) {
            for (const std::string& spec : specs) {
                if (selected_method(sel, M::name) && selected(sel, spec, robust)) {
                    subjects.push_back(
                        {M::name, robust, !IntersectionMethod<M>, spec, 0, 0, {}, 0});
                }
            }
        }
    });
    for (const std::string& spec : specs) {
        if (selected_method(sel, exact_subject) && selected(sel, spec, true)) {
            subjects.push_back({exact_subject, true, false, spec, 0, 0, {}, 0});
        }
    }
    return subjects;
}

}  // namespace

std::vector<Row> leak_rows(std::string_view case_name,
                           const std::vector<Scene>& scenes,
                           const LeakRays& rays_for,
                           const Selection& sel) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const std::vector<std::string> specs = leak_case_specs();
    // One subject per (method, robust, spec), tallied over every scene.
    std::vector<Subject> subjects = leak_subjects(specs, sel);
    ExactReference ref;
    for (const std::string& spec : specs) {
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            std::vector<Rayf> rays;
            for (Subject& sub : subjects) {
                if (sub.spec != spec) {
                    continue;
                }
                const SceneTracer tracer = subject_tracer(scenes[k], sub, spec);
                if (rays.empty()) {
                    rays = rays_for(k, tracer);
                }
                const Stopwatch sw;
                const std::vector<Hit> hits = trace_all(tracer, rays, sub.any);
                sub.ns += sw.ns();
                sub.rays += rays.size();
                tally_subject(sub, scenes[k], k, rays, hits, ref);
            }
        }
    }
    std::vector<Row> rows;
    for (const Subject& sub : subjects) {
        std::string note = leak_note(sub.tally, sub.robust);
        if (sub.any) {
            note = "any-hit (occlusion-only method)" + (note.empty() ? "" : "; " + note);
        }
        const bool exact = sub.method == exact_subject;
        if (exact && sub.disagree > 0) {
            note += (note.empty() ? "" : "; ") + std::to_string(sub.disagree) +
                    " hits differ from exact brute force's (a bug)";
        }
        Row row = make_row(std::string(case_name),
                           std::string(sub.method) + " + " + sub.spec + " " +
                               (exact ? "certified" : robust_label(sub.robust)),
                           "float", sub.rays, sub.tally.leaks, "leaks",
                           sub.ns / static_cast<double>(std::max<std::size_t>(sub.rays, 1)), note);
        row.defect = (sub.robust && sub.tally.lost > 0) || (exact && sub.tally.leaks > 0) ||
                     sub.disagree > 0;
        rows.push_back(std::move(row));
    }
    return rows;
}

std::vector<Row> run_watertight(const Options& opt, const Selection& sel) {
    const std::vector<Scene> scenes{mesh_scene(watertight_sphere(opt.seed))};
    const std::vector<Rayf> rays = inside_rays(scenes[0].meshes[0].mesh, opt.rays, opt.seed);
    return leak_rows(
        "watertight", scenes, [&](std::size_t, const SceneTracer&) { return rays; }, sel);
}

}  // namespace rtlab::stab
