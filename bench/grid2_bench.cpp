// The two-level grid's targets and the one cost model (`rtlab_bench --suite grid2`),
// every row in one process, on the same primitives and rays, TBB limited to one thread:
//   grid2/trace/<spec>/<scene>/<kind>/threads:1
//       every registry row but brute (default parameters; --accel narrows the list) through
//       SceneTracer. Counters: rays/s, nodes/ray and prims/ray (a separate counting pass),
//       cost_model (accel/cost_model.h, the spec's ct and ci), measured_cost (ct * nodes/ray +
//       ci * prims/ray), epo (BVH layouts over triangles), build_ms, prims.
//   grid2/build/<spec>/<scene>/threads:<1|2>  build time from the scene's triangle bounds;
//       build_ms is the median of the timed builds.
// Scenes: flake_meshfloor3 (the tessellated SF 3 flake with its floor), stadium, flake_spheres4
// (analytic; trace rows only); --quick uses flake_meshfloor2, stadium and flake_spheres2.
// Rays: primary, shadow (any hit), diffuse.
#include "accel/any_accel.h"
#include "accel/cost_model.h"
#include "bench/benchmarks.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

constexpr RayKind grid2_kinds[] = {RayKind::primary, RayKind::shadow, RayKind::diffuse};

std::vector<std::string> mesh_scenes() {
    return {quick_mode() ? "flake_meshfloor2" : "flake_meshfloor3", "stadium"};
}

/// The tracer of (scene, spec), one at a time (rows are registered grouped by tracer).
const SceneTracer& tracer(const std::string& scene, const std::string& spec) {
    static std::unique_ptr<SceneTracer> last;
    static std::string last_key;
    const std::string key = scene + "|" + spec;
    if (!last || last_key != key) {
        last.reset();
        TraceSetup setup;
        setup.accel = parse_accel_spec(spec);
        last = std::make_unique<SceneTracer>(bench_scene(scene).scene, setup);
        last_key = key;
    }
    return *last;
}

void bm_trace(benchmark::State& state, std::string spec, std::string scene, RayKind kind) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const std::vector<Rayf>& rays = bench_scene(scene).rays.at(kind);
    const SceneTracer& t = tracer(scene, spec);
    const TraversalStats st = time_and_count(state, t, rays, kind);
    const auto n = static_cast<double>(rays.size());
    const double nodes = static_cast<double>(st.nodes) / n;
    const double prims = static_cast<double>(st.prims) / n;
    const CostParams p = cost_params(t.accel_spec());
    double model = 0, epo = -1;
    for (const auto& [expected, e] : t.cost_figures(p, kind == RayKind::primary)) {
        model += expected.cost(p);
        epo = std::max(epo, e);
    }
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["nodes/ray"] = nodes;
    state.counters["prims/ray"] = prims;
    state.counters["cost_model"] = model;
    state.counters["measured_cost"] = measured_cost(p, nodes, prims);
    if (epo >= 0) {
        state.counters["epo"] = epo;
    }
    state.counters["build_ms"] = t.build_ms();
    state.counters["prims"] = static_cast<double>(t.primitive_count());
}

void bm_build(benchmark::State& state, std::string spec, std::string scene, int threads) {
    const std::vector<Bounds3f> bounds = triangle_bounds(bench_scene(scene).scene);
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    std::vector<double> ms;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        AnyAccel a = build_accel(spec, BuildInput{bounds, {}});
        const auto t1 = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(t1 - t0).count();
        state.SetIterationTime(s);
        ms.push_back(1e3 * s);
        benchmark::DoNotOptimize(a);
    }
    std::sort(ms.begin(), ms.end());
    state.counters["prims"] = static_cast<double>(bounds.size());
    state.counters["build_ms"] = ms[ms.size() / 2];
}

}  // namespace

void rtlab::bench::register_grid2_benchmarks() {
    std::vector<std::string> scenes = mesh_scenes();
    scenes.push_back(quick_mode() ? "flake_spheres2" : "flake_spheres4");
    for (const std::string& spec : bench_specs()) {
        for (const std::string& scene : scenes) {
            for (RayKind k : grid2_kinds) {
                const std::string name = "grid2/trace/" + spec + "/" + scene + "/" +
                                         std::string(to_string(k)) + "/threads:1";
                benchmark::RegisterBenchmark(name.c_str(), bm_trace, spec, scene, k)
                    ->Unit(benchmark::kMillisecond)
                    ->Repetitions(quick_mode() ? 1 : 3)
                    ->ReportAggregatesOnly(!quick_mode())
                    ->MinTime(quick_mode() ? 0.01 : 0.2)
                    ->UseRealTime();
            }
        }
    }
    for (const std::string& spec : bench_specs()) {
        for (const std::string& scene : mesh_scenes()) {
            for (int threads : {1, 2}) {
                const std::string name =
                    "grid2/build/" + spec + "/" + scene + "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), bm_build, spec, scene, threads)
                    ->Unit(benchmark::kMillisecond)
                    ->UseManualTime()
                    ->Iterations(quick_mode() ? 1 : 3);
            }
        }
    }
}
