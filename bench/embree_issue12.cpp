// Embree's side of issue 12's target measurements (`rtlab_bench --suite issue12`; ours in
// issue12_bench.cpp), on the same scenes and rays:
//   issue12/trace/embree:<quality>/default/plain/<scene>/<kind>/threads:<k>  rtcIntersect1 /
//       rtcOccluded1 per ray, TBB limited to k threads. Counters: rays/s, build_ms, prims,
//       bytes/prim (everything Embree allocated for the scene, geometry copies included, from
//       its memory monitor), agree and agree_hits (embree_agreement on the first 1000 rays).
//   issue12/build/embree:<quality>/<scene>/threads:<k>  rtcCommitScene of the mesh scene's
//       triangles; build_ms is the median of the timed commits.
#include "bench/benchmarks.h"
#include "bench/embree_scene.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

constexpr RayKind issue_kinds[] = {RayKind::primary, RayKind::shadow, RayKind::diffuse};

void bm_trace(
    benchmark::State& state, EmbreeQuality q, std::string scene, RayKind kind, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    if (const BuiltScene* built = run_embree_trace(state, scene, q.quality, kind)) {
        state.counters["bytes/prim"] =
            static_cast<double>(built->scene->bytes()) / state.counters["prims"].value;
    }
}

void bm_build(benchmark::State& state, EmbreeQuality q, std::string scene, int threads) {
    const Scene& s = bench_scene(scene).scene;
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    std::vector<double> ms;
    double bytes = 0;
    for (auto _ : state) {
        EmbreeScene e(s, q.quality);  // geometry upload: not timed
        const double t = e.commit();
        state.SetIterationTime(1e-3 * t);
        ms.push_back(t);
        bytes = static_cast<double>(e.bytes());
    }
    std::sort(ms.begin(), ms.end());
    const auto prims = static_cast<double>(embree_primitive_count(s));
    state.counters["prims"] = prims;
    state.counters["build_ms"] = ms[ms.size() / 2];
    state.counters["bytes/prim"] = bytes / prims;
}

}  // namespace

void rtlab::bench::register_issue12_embree_benchmarks() {
    const std::string mesh = issue12_mesh_scene();
    std::vector<std::string> scenes{mesh};
    for (const std::string& s : issue12_sphere_scenes()) {
        scenes.push_back(s);
    }
    for (const EmbreeQuality& q : embree_qualities) {
        const std::string accel = std::string("embree:") + q.name;
        for (const std::string& scene : scenes) {
            for (RayKind k : issue_kinds) {
                for (int threads : {1, 2}) {
                    if (threads == 2 && scene != mesh) {
                        continue;
                    }
                    const std::string name = "issue12/trace/" + accel + "/default/plain/" + scene +
                                             "/" + std::string(to_string(k)) +
                                             "/threads:" + std::to_string(threads);
                    issue12_timing(
                        benchmark::RegisterBenchmark(name.c_str(), bm_trace, q, scene, k, threads)
                            ->UseRealTime());
                }
            }
        }
        for (int threads : {1, 2}) {
            const std::string name =
                "issue12/build/" + accel + "/" + mesh + "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), bm_build, q, mesh, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseManualTime()
                ->Iterations(quick_mode() ? 1 : 5);
        }
    }
}
