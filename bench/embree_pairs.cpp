// Embree's side of the BVH layouts' target measurements (`rtlab_bench --suite targets`; ours in
// targets_bench.cpp), on the same scenes and rays:
//   targets/trace/embree:<quality>/default/plain/<scene>/<kind>/threads:<k>  rtcIntersect1 /
//       rtcOccluded1 per ray, TBB limited to k threads. Counters: rays/s, build_ms, prims,
//       bytes/prim (everything Embree allocated for the scene, geometry copies included, from
//       its memory monitor), agree and agree_hits (embree_agreement on the first 1000 rays).
//   targets/build/embree:<quality>/<scene>/threads:<k>  rtcCommitScene of the mesh scene's
//       triangles; build_ms is the median of the timed commits.
//   targets/paired/<spec>/<methods>/<plain|robust>/<scene>/<kind>/threads:1  our tracer for the
//       row (the wide layouts and bvh:pair) against Embree medium, one thread, timed in
//       alternation: each pair is one sample of ours and one of Embree's (order swapped from
//       pair to pair), each sample one untimed pass over the rays, then enough timed passes to
//       last >= 20 ms; 3 repetitions of 7 pairs. Counters per repetition: ratio (median over the
//       pairs of Embree's time / ours: our speed in Embree's), ratio_q1 and ratio_q3 (quartiles),
//       pairs, passes; reported as aggregates (median, min, max, ...). A load burst on a shared
//       machine slows both halves of a pair, so the ratio holds still where separate medians
//       drift.
//   targets/paired_build/<spec>/<scene>/threads:1  our build of the row (bvh:pbinned and the
//       wide layouts) from the triangle bounds against Embree medium's rtcCommitScene (geometry
//       upload untimed), one thread, in alternation (order swapped from pair to pair). 3
//       repetitions of 5 pairs. Counters: ratio (median over the pairs of our time / Embree's:
//       lower is faster), ratio_q1, ratio_q3, pairs; aggregates as above.
//   targets/scaling/embree:<quality>/<build|kind>/<scene>/threads:2  Embree's commit (both
//       qualities) or medium's trace of the mesh scene with TBB limited to one thread and to two,
//       in alternation (bench/paired.h); ratio is the median speed-up, as for our rows.
#include "bench/benchmarks.h"
#include "bench/embree_scene.h"
#include "bench/paired.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <string>
#include <tbb/global_control.h>
#include <utility>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

constexpr RayKind target_kinds[] = {RayKind::primary, RayKind::shadow, RayKind::diffuse};

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

void bm_paired(benchmark::State& state, TargetsKey key, RayKind kind) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const BuiltScene* built = nullptr;
    try {
        built = &cached_embree_scene(key.scene, RTC_BUILD_QUALITY_MEDIUM);
    } catch (const std::exception& ex) {
        state.SkipWithError(ex.what());
        return;
    }
    const SceneTracer& t = targets_tracer(key);
    const std::vector<Rayf>& rays = bench_scene(key.scene).rays.at(kind);
    TracePass mine(rays.size());
    EmbreePass embree(rays.size());
    const auto ours = [&] { mine.run(t, rays, kind); };
    const auto theirs = [&] { embree.run(*built->scene, rays, kind); };
    // As many passes as make the slower side's sample last the minimum (the same count for both,
    // so a pair compares equal work).
    const double one = std::max(seconds_of(1, ours), seconds_of(1, theirs));
    const int passes = passes_for(targets_min_sample(), one);
    std::vector<double> ratios;
    for (const PairTimes& p : alternate(
             state, [&] { return seconds_of(passes, ours); },
             [&] { return seconds_of(passes, theirs); })) {
        ratios.push_back(p.second / p.first);  // Embree's time over ours
    }
    set_ratio_counters(state, std::move(ratios));
    state.counters["passes"] = passes;
}

void bm_paired_build(benchmark::State& state, std::string spec, std::string scene) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const Scene& s = bench_scene(scene).scene;
    const std::vector<Bounds3f> bounds = triangle_bounds(s);
    const BuildInput in{bounds, {}, triangle_extent(s)};
    const auto ours = [&] { return seconds_to_build(spec, in); };
    const auto theirs = [&] {
        EmbreeScene e(s, RTC_BUILD_QUALITY_MEDIUM);  // geometry upload: not timed
        return 1e-3 * e.commit();
    };
    std::vector<double> ratios;
    for (const PairTimes& p : alternate(state, ours, theirs)) {
        ratios.push_back(p.first / p.second);  // our time over Embree's
    }
    set_ratio_counters(state, std::move(ratios));
}

void bm_scaling_build(benchmark::State& state, EmbreeQuality q, std::string scene) {
    const Scene& s = bench_scene(scene).scene;
    time_scaling(state, [&] {
        EmbreeScene e(s, q.quality);  // geometry upload: not timed
        return 1e-3 * e.commit();
    });
}

void bm_scaling_trace(benchmark::State& state, std::string scene, RayKind kind) {
    const BuiltScene* built = nullptr;
    try {
        built = &cached_embree_scene(scene, RTC_BUILD_QUALITY_MEDIUM);
    } catch (const std::exception& ex) {
        state.SkipWithError(ex.what());
        return;
    }
    const std::vector<Rayf>& rays = bench_scene(scene).rays.at(kind);
    EmbreePass embree(rays.size());
    time_scaling_passes(state, targets_min_sample(),
                        [&] { embree.run(*built->scene, rays, kind); });
}

void register_paired(const std::vector<std::string>& scenes, const std::string& mesh) {
    for (const std::string& spec : targets_layout_specs()) {
        if (!targets_paired_layout(spec)) {
            continue;
        }
        for (const std::string& scene : scenes) {
            for (const bool wt : {false, true}) {
                if (wt && scene != mesh) {
                    continue;
                }
                for (RayKind k : target_kinds) {
                    const std::string name = "targets/paired/" + spec +
                                             (wt ? "/watertight/robust/" : "/default/plain/") +
                                             scene + "/" + std::string(to_string(k)) + "/threads:1";
                    targets_paired_timing(
                        benchmark::RegisterBenchmark(name.c_str(), bm_paired,
                                                     TargetsKey{scene, spec, wt}, k),
                        7);
                }
            }
        }
    }
}

}  // namespace

void rtlab::bench::register_targets_embree_benchmarks() {
    const std::string mesh = targets_mesh_scene();
    std::vector<std::string> scenes{mesh};
    for (const std::string& s : targets_sphere_scenes()) {
        scenes.push_back(s);
    }
    for (const EmbreeQuality& q : embree_qualities) {
        const std::string accel = std::string("embree:") + q.name;
        for (const std::string& scene : scenes) {
            for (RayKind k : target_kinds) {
                for (int threads : {1, 2}) {
                    if (threads == 2 && scene != mesh) {
                        continue;
                    }
                    const std::string name = "targets/trace/" + accel + "/default/plain/" + scene +
                                             "/" + std::string(to_string(k)) +
                                             "/threads:" + std::to_string(threads);
                    targets_timing(
                        benchmark::RegisterBenchmark(name.c_str(), bm_trace, q, scene, k, threads)
                            ->UseRealTime());
                }
            }
        }
        for (int threads : {1, 2}) {
            const std::string name =
                "targets/build/" + accel + "/" + mesh + "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), bm_build, q, mesh, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseManualTime()
                ->Iterations(quick_mode() ? 1 : 5);
        }
    }
    register_paired(scenes, mesh);
    for (const EmbreeQuality& q : embree_qualities) {
        const std::string name =
            std::string("targets/scaling/embree:") + q.name + "/build/" + mesh + "/threads:2";
        targets_paired_timing(benchmark::RegisterBenchmark(name.c_str(), bm_scaling_build, q, mesh),
                              7);
    }
    for (RayKind k : target_kinds) {
        const std::string name = "targets/scaling/embree:medium/" + std::string(to_string(k)) +
                                 "/" + mesh + "/threads:2";
        targets_paired_timing(benchmark::RegisterBenchmark(name.c_str(), bm_scaling_trace, mesh, k),
                              7);
    }
    // The builds the target table sets against Embree medium's: the binary default and the wide
    // layouts' (the table shows the one whose trace is fastest).
    for (const std::string& spec : targets_layout_specs()) {
        const bool wide = targets_paired_layout(spec) && !spec.starts_with("bvh:pair,");
        if (!spec.starts_with("bvh:pbinned,") && !wide) {
            continue;
        }
        const std::string name = "targets/paired_build/" + spec + "/" + mesh + "/threads:1";
        targets_paired_timing(
            benchmark::RegisterBenchmark(name.c_str(), bm_paired_build, spec, mesh), 5);
    }
}
