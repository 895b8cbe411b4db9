// Build benchmarks build/<structure>/soup/<prims>/threads:<k>: build time of every registered
// structure and builder over a triangle-soup size sweep, with TBB limited to k threads
// (tbb::global_control max_allowed_parallelism). bvh:pbinned (and the layouts converted from
// it) build in parallel; the other builders are single-threaded, so threads:2 equals threads:1
// for them up to noise (quick mode registers only threads:1); Embree's builder
// (embree_bench.cpp) uses the second thread too. Timed: the build call only,
// from prepared bounds plus SceneTracer's exact triangle clip (kd-tree perfect splits, grid cell
// overlap). Counters: prims, build_ms, bytes/prim, sah_cost, nodes.
#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "bench/trace_fixture.h"
#include "trace/clip.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

void bm_build(benchmark::State& state, std::string accel, int sf, int threads) {
    const Scene& scene = build_soup(sf);
    const TriangleMesh& mesh = scene.meshes.front().mesh;
    const std::vector<Bounds3f> bounds = triangle_bounds(scene);
    const ClipFn clip = [&mesh](std::uint32_t i, const Bounds3f& box) {
        const auto& t = mesh.triangles[i];
        return clip_triangle_bounds(mesh.positions[t[0]], mesh.positions[t[1]],
                                    mesh.positions[t[2]], box);
    };
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    AccelInfo info;
    double total_ms = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        AnyAccel a = build_accel(accel, BuildInput{bounds, clip});
        const auto t1 = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(t1 - t0).count();
        state.SetIterationTime(s);
        total_ms += 1e3 * s;
        info = accel_info(a);
        benchmark::DoNotOptimize(a);
    }
    state.counters["prims"] = static_cast<double>(bounds.size());
    state.counters["build_ms"] = total_ms / static_cast<double>(state.iterations());
    state.counters["bytes/prim"] = info.bytes_per_prim;
    state.counters["sah_cost"] = info.sah_cost;
    state.counters["nodes"] = static_cast<double>(info.nodes);
}

}  // namespace

void rtlab::bench::register_build_benchmarks() {
    for (const std::string& spec : bench_specs()) {
        for (int sf : build_soup_sizes()) {
            const std::size_t prims = std::size_t{1024} << sf;
            for (int threads : {1, 2}) {
                if (threads > 1 && quick_mode()) {
                    continue;  // identical to threads:1 for our single-threaded builders
                }
                const std::string name = "build/" + spec + "/soup/" + std::to_string(prims) +
                                         "/threads:" + std::to_string(threads);
                quick_time(benchmark::RegisterBenchmark(name.c_str(), bm_build, spec, sf, threads)
                               ->Unit(benchmark::kMillisecond)
                               ->UseManualTime());
            }
        }
    }
}
