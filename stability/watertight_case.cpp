// Watertightness (pbrt's "Triangle, Watertight" idea, the stability suite's first case): rays from
// inside a closed, vertex-perturbed sphere mesh, in random directions and aimed exactly at vertices
// and shared edges, must all hit. Every triangle method x every structure x robust on/off, float,
// traced through SceneTracer (the path `rtlab trace` takes); a ray that hits nothing is a leak.
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

std::vector<Row> leak_rows(std::string_view case_name,
                           const std::vector<Scene>& scenes,
                           const LeakRays& rays_for,
                           const Selection& sel) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const std::vector<std::string> specs = leak_case_specs();
    // One subject per (method, robust, spec), tallied over every scene.
    struct Subject {
        std::string_view method;
        bool robust = false;
        bool any = false;
        std::string spec;
        std::size_t rays = 0;
        double ns = 0;
        LeakTally tally;
    };
    std::vector<Subject> subjects;
    for_each_type<TriangleMethods<float>>([&]<class M>() {
        for (const bool robust : {false, true}) {
            for (const std::string& spec : specs) {
                if (selected_method(sel, M::name) && selected(sel, spec, robust)) {
                    subjects.push_back({M::name, robust, !IntersectionMethod<M>, spec, 0, 0, {}});
                }
            }
        }
    });
    for (const std::string& spec : specs) {
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            const TriangleMesh& mesh = scenes[k].meshes[0].mesh;
            std::vector<Rayf> rays;
            for_each_type<TriangleMethods<float>>([&]<class M>() {
                for (Subject& sub : subjects) {
                    if (sub.method != M::name || sub.spec != spec) {
                        continue;
                    }
                    TraceSetup setup;
                    setup.accel = parse_accel_spec(spec);
                    setup.methods = {std::string(sub.method)};
                    setup.robust = sub.robust;
                    const SceneTracer tracer(scenes[k], setup);
                    if (rays.empty()) {
                        rays = rays_for(k, tracer);
                    }
                    const Stopwatch sw;
                    const std::vector<Hit> hits = trace_all(tracer, rays, sub.any);
                    sub.ns += sw.ns();
                    sub.rays += rays.size();
                    tally_leaks<M>(mesh, rays, hits, sub.tally);
                }
            });
        }
    }
    std::vector<Row> rows;
    for (const Subject& sub : subjects) {
        std::string note = leak_note(sub.tally, sub.robust);
        if (sub.any) {
            note = "any-hit (occlusion-only method)" + (note.empty() ? "" : "; " + note);
        }
        Row row =
            make_row(std::string(case_name),
                     std::string(sub.method) + " + " + sub.spec + " " + robust_label(sub.robust),
                     "float", sub.rays, sub.tally.leaks, "leaks",
                     sub.ns / static_cast<double>(std::max<std::size_t>(sub.rays, 1)), note);
        row.defect = sub.robust && sub.tally.lost > 0;
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
