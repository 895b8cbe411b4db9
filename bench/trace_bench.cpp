// Traversal benchmarks: structure x scene x ray kind, every structure tracing the same fixed rays
// (cached per scene and kind). Counters: rays/s, and nodes/ray and prims/ray from a separate
// counting pass so counting never perturbs the timing.
#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "datasets_gen/generators.h"
#include "trace/ray_gen.h"
#include "trace/scene_tracer.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace rtlab;

constexpr std::size_t ray_count = 16384;

/// A generated scene and its ray sets, built once per process.
struct SceneFixture {
    Scene scene;
    std::map<RayKind, std::vector<Rayf>> rays;
};

const SceneFixture& scene_fixture(const std::string& name) {
    static std::map<std::string, std::unique_ptr<SceneFixture>> cache;
    auto& slot = cache[name];
    if (!slot) {
        slot = std::make_unique<SceneFixture>();
        gen::GenOptions o;
        o.size = name == "soup" ? 6 : 2;
        o.as_mesh = name == "flake_mesh";
        slot->scene = gen::generate(name == "soup" ? "soup" : "flake", o);
        for (RayKind k : {RayKind::primary, RayKind::shadow, RayKind::diffuse, RayKind::random}) {
            slot->rays[k] = make_rays(slot->scene, k, ray_count, 1);
        }
    }
    return *slot;
}

const SceneTracer& tracer(const std::string& scene, const std::string& accel) {
    static std::map<std::pair<std::string, std::string>, std::unique_ptr<SceneTracer>> cache;
    auto& slot = cache[{scene, accel}];
    if (!slot) {
        TraceSetup setup;
        setup.accel = accel;
        slot = std::make_unique<SceneTracer>(scene_fixture(scene).scene, setup);
    }
    return *slot;
}

void bm_trace(benchmark::State& state, std::string accel, std::string scene, RayKind kind) {
    const std::vector<Rayf>& rays = scene_fixture(scene).rays.at(kind);
    const SceneTracer& t = tracer(scene, accel);
    std::vector<Hit> hits(rays.size());
    std::vector<std::uint32_t> blockers(rays.size());
    for (auto _ : state) {
        if (kind == RayKind::shadow) {
            t.occluded(rays, blockers);
            benchmark::DoNotOptimize(blockers.data());
        } else {
            t.intersect(rays, hits);
            benchmark::DoNotOptimize(hits.data());
        }
    }
    TraversalStats st;
    if (kind == RayKind::shadow) {
        t.occluded(rays, blockers, &st);
    } else {
        t.intersect(rays, hits, &st);
    }
    const auto n = static_cast<double>(rays.size());
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["nodes/ray"] = static_cast<double>(st.nodes) / n;
    state.counters["prims/ray"] = static_cast<double>(st.prims) / n;
    state.counters["build_ms"] = t.build_ms();
}

}  // namespace

void rtlab::bench::register_trace_benchmarks() {
    for (const AccelEntry& e : accel_registry()) {
        if (e.name == "brute") {
            continue;  // O(N) per ray: the reference for correctness, not a contender
        }
        for (const char* scene : {"flake_mesh", "flake_spheres", "soup"}) {
            for (RayKind k :
                 {RayKind::primary, RayKind::shadow, RayKind::diffuse, RayKind::random}) {
                const std::string name =
                    "trace/" + std::string(e.name) + "/" + scene + "/" + std::string(to_string(k));
                benchmark::RegisterBenchmark(name.c_str(), bm_trace, std::string(e.name),
                                             std::string(scene), k)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
            }
        }
    }
}
