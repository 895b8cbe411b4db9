// Embree's side of issue 12's target measurements (`rtlab_bench --suite issue12`; ours in
// issue12_bench.cpp), on the same scenes and rays:
//   issue12/trace/embree:<quality>/default/plain/<scene>/<kind>/threads:<k>  rtcIntersect1 /
//       rtcOccluded1 per ray, TBB limited to k threads. Counters: rays/s, build_ms, prims,
//       bytes/prim (everything Embree allocated for the scene, geometry copies included, from
//       its memory monitor), agree and agree_hits (embree_agreement on the first 1000 rays).
//   issue12/build/embree:<quality>/<scene>/threads:<k>  rtcCommitScene of the mesh scene's
//       triangles; build_ms is the median of the timed commits.
//   issue12/paired/<spec>/<methods>/<plain|robust>/<scene>/<kind>/threads:1  our tracer for the
//       row (the wide layouts and bvh:pair) against Embree medium, one thread, timed in
//       alternation: each pair is one sample of ours and one of Embree's (order swapped from
//       pair to pair), each sample one untimed pass over the rays, then enough timed passes to
//       last >= 20 ms. Counters: ratio (median over the pairs of Embree's time / ours: our speed
//       in Embree's), ratio_q1 and ratio_q3 (quartiles), pairs, passes. A load burst on a shared
//       machine slows both halves of a pair, so the ratio holds still where separate medians
//       drift.
//   issue12/paired_build/<spec>/<scene>/threads:1  our build of the row (bvh:pbinned and the
//       fastest layout, bvh8) from the triangle bounds against Embree medium's rtcCommitScene
//       (geometry upload untimed), one thread, in alternation (order swapped from pair to pair).
//       Counters: ratio (median over the pairs of our time / Embree's: lower is faster),
//       ratio_q1, ratio_q3, pairs.
#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "bench/embree_scene.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <tbb/global_control.h>
#include <utility>
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

/// Wall seconds one call of f takes.
template <class F>
double seconds_once(const F& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Wall seconds of `passes` calls of f, after one untimed call (the other side's sample has just
/// filled the caches with its own data).
template <class F>
double seconds_of(int passes, const F& f) {
    f();
    return seconds_once([&] {
        for (int p = 0; p < passes; ++p) {
            f();
        }
    });
}

/// The value at fraction q of sorted v (nearest rank).
double quantile(const std::vector<double>& v, double q) {
    return v[static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

/// The median and quartiles of the per-pair ratios, and their count, as the row's counters.
void set_ratio_counters(benchmark::State& state, std::vector<double> ratios) {
    std::sort(ratios.begin(), ratios.end());
    state.counters["ratio"] = quantile(ratios, 0.5);
    state.counters["ratio_q1"] = quantile(ratios, 0.25);
    state.counters["ratio_q3"] = quantile(ratios, 0.75);
    state.counters["pairs"] = static_cast<double>(ratios.size());
}

void bm_paired(benchmark::State& state, Issue12Key key, RayKind kind) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const BuiltScene* built = nullptr;
    try {
        built = &cached_embree_scene(key.scene, RTC_BUILD_QUALITY_MEDIUM);
    } catch (const std::exception& ex) {
        state.SkipWithError(ex.what());
        return;
    }
    const SceneTracer& t = issue12_tracer(key);
    const std::vector<Rayf>& rays = bench_scene(key.scene).rays.at(kind);
    TracePass mine(rays.size());
    EmbreePass embree(rays.size());
    const auto ours = [&] { mine.run(t, rays, kind); };
    const auto theirs = [&] { embree.run(*built->scene, rays, kind); };
    // As many passes as make the slower side's sample last the minimum (the same count for both,
    // so a pair compares equal work).
    const double min_sample = quick_mode() ? 0.002 : 0.02;
    const double one = std::max(seconds_of(1, ours), seconds_of(1, theirs));
    const int passes = std::max(1, static_cast<int>(std::ceil(min_sample / std::max(one, 1e-9))));
    std::vector<double> ratios;
    for (auto _ : state) {
        const bool ours_first = ratios.size() % 2 == 0;
        double t_ours = 0, t_embree = 0;
        if (ours_first) {
            t_ours = seconds_of(passes, ours);
            t_embree = seconds_of(passes, theirs);
        } else {
            t_embree = seconds_of(passes, theirs);
            t_ours = seconds_of(passes, ours);
        }
        state.SetIterationTime(t_ours + t_embree);
        ratios.push_back(t_embree / t_ours);
    }
    set_ratio_counters(state, std::move(ratios));
    state.counters["passes"] = passes;
}

void bm_paired_build(benchmark::State& state, std::string spec, std::string scene) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const Scene& s = bench_scene(scene).scene;
    const std::vector<Bounds3f> bounds = triangle_bounds(s);
    const auto ours = [&] {
        std::optional<AnyAccel> a;
        const double t = seconds_once([&] {
            a.emplace(build_accel(spec, BuildInput{bounds, {}}));
        });
        benchmark::DoNotOptimize(a);
        return t;  // the structure is freed after the clock stopped, as Embree's scene below
    };
    const auto theirs = [&] {
        EmbreeScene e(s, RTC_BUILD_QUALITY_MEDIUM);  // geometry upload: not timed
        return 1e-3 * e.commit();
    };
    std::vector<double> ratios;
    for (auto _ : state) {
        double t_ours = 0, t_embree = 0;
        if (ratios.size() % 2 == 0) {
            t_ours = ours();
            t_embree = theirs();
        } else {
            t_embree = theirs();
            t_ours = ours();
        }
        state.SetIterationTime(t_ours + t_embree);
        ratios.push_back(t_ours / t_embree);
    }
    set_ratio_counters(state, std::move(ratios));
}

/// The layouts the paired rows run: the wide ones and bvh:pair (the best layouts of the table).
bool paired_layout(const std::string& spec) {
    return spec.starts_with("bvh4,") || spec.starts_with("bvh8,") || spec.starts_with("bvh8q,") ||
           spec.starts_with("bvh:pair,");
}

void register_paired(const std::vector<std::string>& scenes, const std::string& mesh) {
    for (const std::string& spec : issue12_layout_specs()) {
        if (!paired_layout(spec)) {
            continue;
        }
        for (const std::string& scene : scenes) {
            for (const bool wt : {false, true}) {
                if (wt && scene != mesh) {
                    continue;
                }
                for (RayKind k : issue_kinds) {
                    const std::string name = "issue12/paired/" + spec +
                                             (wt ? "/watertight/robust/" : "/default/plain/") +
                                             scene + "/" + std::string(to_string(k)) + "/threads:1";
                    benchmark::RegisterBenchmark(name.c_str(), bm_paired,
                                                 Issue12Key{scene, spec, wt}, k)
                        ->Unit(benchmark::kMillisecond)
                        ->UseManualTime()
                        ->Iterations(quick_mode() ? 3 : 21);
                }
            }
        }
    }
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
    register_paired(scenes, mesh);
    // The builds the target table sets against Embree medium's: the binary default and bvh8's.
    for (const std::string& spec : issue12_layout_specs()) {
        if (!spec.starts_with("bvh:pbinned,") && !spec.starts_with("bvh8,")) {
            continue;
        }
        const std::string name = "issue12/paired_build/" + spec + "/" + mesh + "/threads:1";
        benchmark::RegisterBenchmark(name.c_str(), bm_paired_build, spec, mesh)
            ->Unit(benchmark::kMillisecond)
            ->UseManualTime()
            ->Iterations(quick_mode() ? 3 : 11);
    }
}
