// Traversal benchmarks trace/<structure>/<scene>/<ray kind>: every registered structure and
// builder (brute force aside) on every benchmark scene (bench/trace_fixture.h) and ray kind, all
// tracing the same fixed rays, with SceneTracer's threading (TBB over rays, all threads).
// Counters: rays/s (timed loop); nodes/ray and prims/ray from a separate counting pass, so
// counting never perturbs the timing; prims, build_ms and bytes/prim over all primitive sets of
// the scene; sah_cost for single-set scenes only (per-set values of mixed scenes such as mount
// are not comparable, so the counter is absent there); cost_model, measured_cost and (BVHs over
// triangles) epo as `rtlab trace --stats` prints them.
#include "accel/any_accel.h"
#include "accel/cost_model.h"
#include "bench/benchmarks.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

void bm_trace(benchmark::State& state, std::string accel, std::string scene, RayKind kind) {
    const std::vector<Rayf>& rays = bench_scene(scene).rays.at(kind);
    const SceneTracer& t = bench_tracer(scene, accel);
    const TraversalStats st = time_and_count(state, t, rays, kind);
    const auto n = static_cast<double>(rays.size());
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["nodes/ray"] = static_cast<double>(st.nodes) / n;
    state.counters["prims/ray"] = static_cast<double>(st.prims) / n;
    state.counters["build_ms"] = t.build_ms();
    state.counters["prims"] = static_cast<double>(t.primitive_count());
    const std::vector<AccelInfo> infos = t.infos();
    double bytes = 0;
    for (const AccelInfo& i : infos) {
        bytes += static_cast<double>(i.bytes);
    }
    state.counters["bytes/prim"] = bytes / static_cast<double>(t.primitive_count());
    if (infos.size() == 1) {
        state.counters["sah_cost"] = infos.front().sah_cost;
    }
    // The one cost model (accel/cost_model.h) with the spec's ct and ci, and the measured cost.
    const CostParams p = cost_params(t.accel_spec());
    double model = 0, epo = -1;
    for (const auto& [expected, e] : t.cost_figures(p, true)) {
        model += expected.cost(p);
        epo = std::max(epo, e);
    }
    state.counters["cost_model"] = model;
    state.counters["measured_cost"] =
        measured_cost(p, state.counters["nodes/ray"], state.counters["prims/ray"]);
    if (epo >= 0) {
        state.counters["epo"] = epo;
    }
}

}  // namespace

void rtlab::bench::register_trace_benchmarks() {
    for (const std::string& spec : bench_specs()) {
        for (const std::string& scene : trace_scene_names()) {
            for (RayKind k : bench_ray_kinds) {
                const std::string name =
                    "trace/" + spec + "/" + scene + "/" + std::string(to_string(k));
                quick_time(benchmark::RegisterBenchmark(name.c_str(), bm_trace, spec, scene, k)
                               ->Unit(benchmark::kMillisecond)
                               ->UseRealTime());
            }
        }
    }
}
