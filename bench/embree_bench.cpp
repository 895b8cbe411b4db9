// Embree 3 baseline for the traversal and build suites, on the same primitives and rays:
//   trace/embree:<quality>/<scene>/<kind>  rtcIntersect1 (rtcOccluded1 for shadow rays), one call
//       per ray, TBB parallel_for over the rays with SceneTracer's grain, all threads: the same
//       threading as our structures (EmbreeScene::intersect). Counters: rays/s, build_ms, prims,
//       agree.
//   build/embree:<quality>/soup/<prims>/threads:<k>  rtcCommitScene with TBB limited to k threads
//       (Embree builds in parallel through TBB). Counters: prims, build_ms.
// Quality is RTC_BUILD_QUALITY_MEDIUM or _HIGH (the latter adds spatial splits for triangles).
// Embree reports no traversal counts, so nodes/ray and prims/ray are absent.
//
// Correctness: before timing, the first 1000 rays are traced by Embree and by our bvh:binned
// SceneTracer; a ray agrees when both miss, or both hit with |t_embree - t_ours| <= 1e-4 |t_ours|
// (shadow rays: both blocked or both free). `agree` is the count of agreeing rays among those
// 1000 and `agree_hits` how many of them hit (so an all-miss set cannot pass unnoticed); more
// than 5 disagreements skip the benchmark with an error.
#include "bench/benchmarks.h"
#include "bench/embree_scene.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <tbb/global_control.h>
#include <utility>
#include <vector>

namespace rtlab::bench {

namespace {
constexpr std::size_t check_rays = 1000;
constexpr std::size_t max_disagreements = 5;
}  // namespace

const BuiltScene& cached_embree_scene(const std::string& scene, RTCBuildQuality q) {
    static std::map<std::pair<std::string, int>, BuiltScene> cache;
    BuiltScene& slot = cache[{scene, static_cast<int>(q)}];
    if (!slot.scene) {
        auto fresh = std::make_unique<EmbreeScene>(bench_scene(scene).scene, q);
        slot.build_ms = fresh->commit();
        slot.scene = std::move(fresh);
    }
    return slot;
}

Agreement embree_agreement(const EmbreeScene& e, const std::string& scene, RayKind kind) {
    const std::vector<Rayf>& all = bench_scene(scene).rays.at(kind);
    const std::span<const Rayf> rays(all.data(), std::min(check_rays, all.size()));
    const SceneTracer& ours = bench_tracer(scene, "bvh:binned");
    Agreement a;
    a.checked = rays.size();
    const auto count = [&a](bool same, bool hit) {
        a.agree += same ? 1 : 0;
        a.hits += same && hit ? 1 : 0;
    };
    if (kind == RayKind::shadow) {
        std::vector<std::uint32_t> blocker(rays.size());
        std::vector<std::uint8_t> blocked(rays.size());
        ours.occluded(rays, blocker);
        e.occluded(rays, blocked);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            count((blocker[i] != invalid_id) == (blocked[i] != 0), blocked[i] != 0);
        }
    } else {
        std::vector<Hit> hits(rays.size());
        std::vector<float> t(rays.size());
        ours.intersect(rays, hits);
        e.intersect(rays, t);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const bool hit = std::isfinite(t[i]);
            if (!hits[i].valid() || !hit) {
                count(hits[i].valid() == hit, false);
            } else {
                count(std::abs(t[i] - hits[i].t) <= 1e-4f * std::abs(hits[i].t), true);
            }
        }
    }
    return a;
}

const BuiltScene* run_embree_trace(benchmark::State& state,
                                   const std::string& scene,
                                   RTCBuildQuality q,
                                   RayKind kind) {
    const BuiltScene* built = nullptr;
    Agreement a;
    try {
        built = &cached_embree_scene(scene, q);
        a = embree_agreement(*built->scene, scene, kind);
    } catch (const std::exception& ex) {
        state.SkipWithError(ex.what());
        return nullptr;
    }
    if (a.checked - a.agree > max_disagreements) {
        const std::string msg = "embree and bvh:binned disagree on " +
                                std::to_string(a.checked - a.agree) + " of " +
                                std::to_string(a.checked) + " rays";
        state.SkipWithError(msg.c_str());
        return nullptr;
    }
    const std::vector<Rayf>& rays = bench_scene(scene).rays.at(kind);
    EmbreePass pass(rays.size());
    for (auto _ : state) {
        pass.run(*built->scene, rays, kind);
    }
    const auto n = static_cast<double>(rays.size());
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["build_ms"] = built->build_ms;
    state.counters["prims"] = static_cast<double>(embree_primitive_count(bench_scene(scene).scene));
    state.counters["agree"] = static_cast<double>(a.agree);
    state.counters["agree_hits"] = static_cast<double>(a.hits);
    return built;
}

}  // namespace rtlab::bench

namespace {

using namespace rtlab;
using namespace rtlab::bench;

void bm_embree_trace(benchmark::State& state, EmbreeQuality q, std::string scene, RayKind kind) {
    run_embree_trace(state, scene, q.quality, kind);
}

void bm_embree_build(benchmark::State& state, EmbreeQuality q, int sf, int threads) {
    const Scene& scene = build_soup(sf);
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    double total_ms = 0;
    for (auto _ : state) {
        EmbreeScene e(scene, q.quality);  // geometry upload: not timed
        const double ms = e.commit();
        state.SetIterationTime(1e-3 * ms);
        total_ms += ms;
    }
    state.counters["prims"] = static_cast<double>(scene.meshes.front().mesh.triangle_count());
    state.counters["build_ms"] = total_ms / static_cast<double>(state.iterations());
}

}  // namespace

void rtlab::bench::register_embree_benchmarks() {
    for (const EmbreeQuality& q : embree_qualities) {
        const std::string accel = std::string("embree:") + q.name;
        for (const std::string& scene : trace_scene_names()) {
            for (RayKind k : bench_ray_kinds) {
                const std::string name =
                    "trace/" + accel + "/" + scene + "/" + std::string(to_string(k));
                quick_time(benchmark::RegisterBenchmark(name.c_str(), bm_embree_trace, q, scene, k)
                               ->Unit(benchmark::kMillisecond)
                               ->UseRealTime());
            }
        }
    }
    for (const EmbreeQuality& q : embree_qualities) {
        for (int sf : build_soup_sizes()) {
            const std::size_t prims = std::size_t{1024} << sf;
            for (int threads : {1, 2}) {
                const std::string name = "build/embree:" + std::string(q.name) + "/soup/" +
                                         std::to_string(prims) +
                                         "/threads:" + std::to_string(threads);
                quick_time(
                    benchmark::RegisterBenchmark(name.c_str(), bm_embree_build, q, sf, threads)
                        ->Unit(benchmark::kMillisecond)
                        ->UseManualTime());
            }
        }
    }
}
