// Watertightness (pbrt's "Triangle, Watertight" idea, case 1 of issue 7): rays from inside a
// closed, vertex-perturbed sphere mesh, in random directions and aimed exactly at vertices and
// shared edges, must all hit. Every triangle method x every structure x robust on/off, float,
// traced through SceneTracer (the path `rtlab trace` takes); a ray that hits nothing is a leak.
#include "intersect/triangle/methods.h"
#include "intersect/triangle/sphere_mesh.h"
#include "scene/scene_io.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
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
                           const Scene& scene,
                           const std::vector<Rayf>& rays,
                           const Selection& sel) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const std::vector<std::string> specs = leak_case_specs();
    std::vector<Row> rows;
    // Every triangle method of the family list, float (occlusion-only ones through any-hit).
    for_each_type<TriangleMethods<float>>([&]<class M>() {
        const std::string_view method = M::name;
        if (!selected_method(sel, method)) {
            return;
        }
        const std::size_t own = method_leaks<M>(scene.meshes[0].mesh, rays);
        for (const bool robust : {false, true}) {
            for (const std::string& spec : specs) {
                if (!selected(sel, spec, robust)) {
                    continue;
                }
                TraceSetup setup;
                setup.accel = spec;
                setup.methods = {std::string(method)};
                setup.robust = robust;
                const SceneTracer tracer(scene, setup);
                const bool any = !IntersectionMethod<M>;
                const Stopwatch sw;
                const std::vector<Hit> hits = trace_all(tracer, rays, any);
                const double ns = sw.ns() / static_cast<double>(rays.size());
                std::size_t leaks = 0;
                for (const Hit& h : hits) {
                    leaks += h.valid() ? 0 : 1;
                }
                std::string note = leak_note(leaks, own, robust);
                if (any) {
                    note = "any-hit (occlusion-only method)" + (note.empty() ? "" : "; " + note);
                }
                rows.push_back(
                    make_row(std::string(case_name),
                             std::string(method) + " + " + spec + " " + robust_label(robust),
                             "float", rays.size(), leaks, "leaks", ns, note));
            }
        }
    });
    return rows;
}

std::vector<Row> run_watertight(const Options& opt, const Selection& sel) {
    const Scene scene = mesh_scene(watertight_sphere(opt.seed));
    return leak_rows("watertight", scene, inside_rays(scene.meshes[0].mesh, opt.rays, opt.seed),
                     sel);
}

}  // namespace rtlab::stab
