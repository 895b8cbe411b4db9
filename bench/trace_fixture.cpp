// Benchmark scenes, ray sets and tracers, generated on first use and cached for the process.
#include "bench/trace_fixture.h"

#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "bench/paired.h"
#include "datasets_gen/generators.h"
#include "scene/scene_setting.h"
#include "trace/clip.h"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

namespace rtlab::bench {

namespace {

// The scene without the objects whose material is called `material`. Keeps order, camera,
// lights, materials.
Scene without_material(const Scene& s, std::string_view material) {
    const int drop = s.find_material(material);
    Scene out = setting_of(s);
    for (const ObjectRef& r : s.order) {
        visit_object(s, r, [&]<class P>(const auto& o) {
            if (drop < 0 || o.material != static_cast<std::uint32_t>(drop)) {
                out.add(o);
            }
        });
    }
    return out;
}

// Parses "<prefix><k>" into k; -1 when name does not start with prefix followed by digits only.
int size_suffix(std::string_view name, std::string_view prefix) {
    if (name.size() <= prefix.size() || name.substr(0, prefix.size()) != prefix) {
        return -1;
    }
    int k = 0;
    for (char c : name.substr(prefix.size())) {
        if (c < '0' || c > '9') {
            return -1;
        }
        k = 10 * k + (c - '0');
    }
    return k;
}

// The scene with every polygon fanned into triangles (one mesh per polygon, same material), so
// Embree, which has no polygon geometry, can trace the same primitives.
Scene polygons_as_meshes(const Scene& s) {
    Scene out = setting_of(s);
    for (const ObjectRef& r : s.order) {
        visit_object(s, r, [&]<class P>(const auto& o) {
            if constexpr (std::is_same_v<std::decay_t<decltype(o)>, PolygonObject>) {
                MeshObject m;
                m.material = o.material;
                m.mesh.positions = o.vertices;
                for (std::uint32_t i = 1; i + 1 < o.vertices.size(); ++i) {
                    m.mesh.triangles.push_back({0, i, i + 1});
                }
                out.add(std::move(m));
            } else {
                out.add(o);
            }
        });
    }
    return out;
}

Scene make_bench_scene(const std::string& name) {
    gen::GenOptions o;
    if (const int k = size_suffix(name, "flake_meshfloor"); k >= 0) {
        o.size = k;
        o.as_mesh = true;
        return polygons_as_meshes(gen::generate("flake", o));
    }
    if (const int k = size_suffix(name, "flake_mesh"); k >= 0) {
        o.size = k;
        o.as_mesh = true;
        return without_material(gen::generate("flake", o), "floor");
    }
    if (const int k = size_suffix(name, "flake_spheres"); k >= 0) {
        o.size = k;
        return without_material(gen::generate("flake", o), "floor");
    }
    if (name == "soup") {
        o.size = 6;
        return gen::generate("soup", o);
    }
    if (name == "stadium") {
        return gen::generate(name, o);  // default size 5
    }
    if (name == "mount") {
        // The seeded fractal terrain (generator `terrain`, called mount before the exact SPD
        // databases took the SPD names), default size 6.
        return gen::generate("terrain", o);
    }
    throw std::invalid_argument("unknown benchmark scene '" + name + "'");
}

}  // namespace

std::size_t bench_ray_count() {
    return quick_mode() ? 4096 : 16384;
}

const BenchScene& bench_scene(const std::string& name) {
    static std::map<std::string, std::unique_ptr<BenchScene>> cache;
    auto& slot = cache[name];
    if (!slot) {
        auto fresh = std::make_unique<BenchScene>();
        fresh->scene = make_bench_scene(name);
        for (RayKind k : bench_ray_kinds) {
            fresh->rays[k] = make_rays(fresh->scene, k, bench_ray_count(), 1);
        }
        slot = std::move(fresh);
    }
    return *slot;
}

std::vector<std::string> trace_scene_names() {
    if (quick_mode()) {
        // No stadium: the grid and the median kd-tree need about a second per 4096 rays there.
        // Two flake sizes, so the report can fit trace time against primitive count.
        return {"flake_mesh1", "flake_mesh2", "flake_spheres1", "flake_spheres2", "soup", "mount"};
    }
    return {"flake_mesh2", "flake_mesh3", "flake_spheres2", "flake_spheres3",
            "soup",        "stadium",     "mount"};
}

const SceneTracer& bench_tracer(const std::string& scene, const std::string& accel) {
    static std::map<std::pair<std::string, std::string>, std::unique_ptr<SceneTracer>> cache;
    auto& slot = cache[{scene, accel}];
    if (!slot) {
        TraceSetup setup;
        setup.accel = parse_accel_spec(accel);
        slot = std::make_unique<SceneTracer>(bench_scene(scene).scene, setup);
    }
    return *slot;
}

void TracePass::run(const SceneTracer& t,
                    const std::vector<Rayf>& rays,
                    RayKind kind,
                    TraversalStats* stats) {
    if (kind == RayKind::shadow) {
        t.occluded(rays, blockers, stats);
        benchmark::DoNotOptimize(blockers.data());
    } else {
        t.intersect(rays, hits, stats);
        benchmark::DoNotOptimize(hits.data());
    }
}

TraversalStats time_and_count(benchmark::State& state,
                              const SceneTracer& t,
                              const std::vector<Rayf>& rays,
                              RayKind kind) {
    TracePass pass(rays.size());
    for (auto _ : state) {
        pass.run(t, rays, kind);
    }
    TraversalStats st;
    pass.run(t, rays, kind, &st);
    return st;
}

std::vector<int> build_soup_sizes() {
    if (quick_mode()) {
        return {0, 2, 4};  // 1024 .. 16384 triangles
    }
    return {0, 2, 4, 6, 8, 10};  // 1024 .. 1048576 triangles
}

const Scene& build_soup(int sf) {
    static std::map<int, std::unique_ptr<Scene>> cache;
    auto& slot = cache[sf];
    if (!slot) {
        gen::GenOptions o;
        o.size = sf;
        slot = std::make_unique<Scene>(gen::generate("soup", o));
    }
    return *slot;
}

std::vector<Bounds3f> triangle_bounds(const Scene& s) {
    std::vector<Bounds3f> out;
    for (const MeshObject& m : s.meshes) {
        for (const auto& t : m.mesh.triangles) {
            Bounds3f b(m.mesh.positions[t[0]]);
            b.extend(m.mesh.positions[t[1]]);
            b.extend(m.mesh.positions[t[2]]);
            out.push_back(b);
        }
    }
    return out;
}

ExtentFn triangle_extent(const Scene& s) {
    auto tris = std::make_shared<std::vector<Trianglef>>();
    for (const MeshObject& m : s.meshes) {
        for (const auto& t : m.mesh.triangles) {
            const auto& p = m.mesh.positions;
            tris->push_back({p[t[0]], p[t[1]], p[t[2]]});
        }
    }
    return [tris](std::uint32_t id, const Vec3f& d) { return shape_extent((*tris)[id], d); };
}

double seconds_to_build(const std::string& spec, const BuildInput& in) {
    std::optional<AnyAccel> a;
    const double t = seconds_once([&] { a.emplace(build_accel(spec, in)); });
    benchmark::DoNotOptimize(a);
    return t;
}

benchmark::internal::Benchmark* quick_time(benchmark::internal::Benchmark* b) {
    return quick_mode() ? b->MinTime(0.02) : b;
}

}  // namespace rtlab::bench
