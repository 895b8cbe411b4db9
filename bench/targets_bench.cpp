// The BVH layouts' target measurements against Embree (`rtlab_bench --suite targets`; Embree's
// side in embree_pairs.cpp), every row on the same primitives and rays:
//   targets/trace/<spec>/<methods>/<plain|robust>/<scene>/<kind>/threads:<k>
//       every BVH-family registry row (name starting with "bvh": binary and wide layouts, default
//       parameters, and accel_variants(): bvh16 with `bounds=dop14`; --accel names the list
//       instead) through SceneTracer with TBB limited to k threads.
//       <methods> is "default" (each family's default method) or "watertight" (the watertight
//       triangle test, with robust traversal: the table's watertight row). Counters: rays/s,
//       nodes/ray and prims/ray (a separate counting pass), bytes/prim (structure) and
//       leaf_bytes/prim (SceneTracer::leaf_bytes: the primitive data traversal reads), build_ms,
//       prims.
//   targets/build/<spec>/<scene>/threads:<k>  build time of the row from the scene's triangle
//       bounds (and, for `bounds=dop14`, the triangles' diagonal extents, as SceneTracer builds),
//       TBB limited to k threads; build_ms is the median of the timed builds.
//   targets/scaling/<spec>/<build|kind>/<scene>/threads:2  the same build (every row) or trace of
//       the mesh scene (the paired layouts) with TBB limited to one thread and to two, timed in
//       alternation (bench/paired.h), 3 repetitions of 7 pairs. Counters per repetition: ratio
//       (median over its pairs of the one-thread time / the two-thread time: the speed-up),
//       ratio_q1, ratio_q3, pairs (and passes); reported as aggregates (median, min, max, ...), as
//       are Embree's paired rows (bench/embree_pairs.cpp).
// Scenes: flake_meshfloor4 (SF 4 tessellated uv:16x8 with the floor as two triangles, 1.65M
// triangles), flake_spheres4 and flake_spheres5 (analytic, no floor); --quick uses sizes 2, 2, 3.
// Rays: primary, shadow (any hit), diffuse. Threads 1, and 2 for the scaling rows on the mesh.
#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "bench/paired.h"
#include "bench/trace_fixture.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace rtlab::bench {

std::string targets_mesh_scene() {
    return quick_mode() ? "flake_meshfloor2" : "flake_meshfloor4";
}

std::vector<std::string> targets_sphere_scenes() {
    if (quick_mode()) {
        return {"flake_spheres2", "flake_spheres3"};
    }
    return {"flake_spheres4", "flake_spheres5"};
}

benchmark::internal::Benchmark* targets_timing(benchmark::internal::Benchmark* b) {
    // Five repetitions, reported as mean, median and spread (the report reads the medians).
    b->Unit(benchmark::kMillisecond)->Repetitions(quick_mode() ? 2 : 5)->ReportAggregatesOnly(true);
    return b->MinTime(quick_mode() ? 0.01 : 0.2);
}

std::vector<std::string> targets_layout_specs() {
    std::vector<std::string> out;
    for (const std::string& s : bench_specs()) {
        if (!s.starts_with("bvh")) {
            continue;
        }
        out.push_back(s);
        // accel_variants() beside their rows' defaults, unless --accel names the list.
        for (const std::string_view v : accel_variants()) {
            const AccelSpec variant = parse_accel_spec(v);
            if (!specs_named() && variant.entry == parse_accel_spec(s).entry) {
                out.push_back(variant.canonical());
            }
        }
    }
    return out;
}

bool targets_paired_layout(const std::string& spec) {
    return spec.starts_with("bvh4,") || spec.starts_with("bvh8,") || spec.starts_with("bvh16,") ||
           spec.starts_with("bvh8q,") || spec.starts_with("bvh:pair,");
}

double targets_min_sample() {
    return quick_mode() ? 0.002 : 0.02;
}

benchmark::internal::Benchmark* targets_paired_timing(benchmark::internal::Benchmark* b,
                                                      int pairs) {
    // Repetitions, which random interleaving spreads over the run, so that a spell in which the
    // shared host gives this process (or its second vCPU) less falls on one repetition of a row
    // rather than on all its pairs; the report takes the median of the repetitions' ratios and
    // shows their range.
    const auto lowest = [](const std::vector<double>& v) { return *std::ranges::min_element(v); };
    const auto highest = [](const std::vector<double>& v) { return *std::ranges::max_element(v); };
    return b->Unit(benchmark::kMillisecond)
        ->UseManualTime()
        ->Iterations(quick_mode() ? 3 : pairs)
        ->Repetitions(quick_mode() ? 2 : 3)
        ->ReportAggregatesOnly(true)
        ->ComputeStatistics("min", +lowest)
        ->ComputeStatistics("max", +highest);
}

const SceneTracer& targets_tracer(const TargetsKey& key) {
    // Benchmarks are registered grouped by key, so each tracer is built once; keeping one at a
    // time bounds memory on the 1.65M-triangle flake.
    static std::unique_ptr<SceneTracer> last;
    static TargetsKey last_key;
    if (!last || !(last_key == key)) {
        last.reset();
        TraceSetup setup;
        setup.accel = parse_accel_spec(key.accel);
        setup.robust = key.watertight;
        if (key.watertight) {
            setup.methods = {"watertight"};
        }
        last = std::make_unique<SceneTracer>(bench_scene(key.scene).scene, setup);
        last_key = key;
    }
    return *last;
}

}  // namespace rtlab::bench

namespace {

using namespace rtlab;
using namespace rtlab::bench;

constexpr RayKind target_kinds[] = {RayKind::primary, RayKind::shadow, RayKind::diffuse};

void bm_trace(benchmark::State& state, TargetsKey key, RayKind kind, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    const std::vector<Rayf>& rays = bench_scene(key.scene).rays.at(kind);
    const SceneTracer& t = targets_tracer(key);
    const TraversalStats st = time_and_count(state, t, rays, kind);
    const auto n = static_cast<double>(rays.size());
    const auto prims = static_cast<double>(t.primitive_count());
    double bytes = 0;
    for (const AccelInfo& i : t.infos()) {
        bytes += static_cast<double>(i.bytes);
    }
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["nodes/ray"] = static_cast<double>(st.nodes) / n;
    state.counters["prims/ray"] = static_cast<double>(st.prims) / n;
    state.counters["build_ms"] = t.build_ms();
    state.counters["prims"] = prims;
    state.counters["bytes/prim"] = bytes / prims;
    state.counters["leaf_bytes/prim"] = static_cast<double>(t.leaf_bytes()) / prims;
}

void bm_build(benchmark::State& state, std::string accel, std::string scene, int threads) {
    const Scene& sc = bench_scene(scene).scene;
    const std::vector<Bounds3f> bounds = triangle_bounds(sc);
    const BuildInput in{bounds, {}, triangle_extent(sc)};
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    std::vector<double> ms;
    AccelInfo info;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        AnyAccel a = build_accel(accel, in);
        const auto t1 = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(t1 - t0).count();
        state.SetIterationTime(s);
        ms.push_back(1e3 * s);
        info = accel_info(a);
        benchmark::DoNotOptimize(a);
    }
    std::sort(ms.begin(), ms.end());
    state.counters["prims"] = static_cast<double>(bounds.size());
    state.counters["build_ms"] = ms[ms.size() / 2];
    state.counters["bytes/prim"] = info.bytes_per_prim;
    state.counters["sah_cost"] = info.sah_cost;
}

void bm_scaling_trace(benchmark::State& state, TargetsKey key, RayKind kind) {
    const std::vector<Rayf>& rays = bench_scene(key.scene).rays.at(kind);
    const SceneTracer& t = targets_tracer(key);
    TracePass mine(rays.size());
    time_scaling_passes(state, targets_min_sample(), [&] { mine.run(t, rays, kind); });
}

void bm_scaling_build(benchmark::State& state, std::string accel, std::string scene) {
    const Scene& sc = bench_scene(scene).scene;
    const std::vector<Bounds3f> bounds = triangle_bounds(sc);
    const BuildInput in{bounds, {}, triangle_extent(sc)};
    time_scaling(state, [&] { return seconds_to_build(accel, in); });
}

}  // namespace

void rtlab::bench::register_targets_benchmarks() {
    const std::string mesh = targets_mesh_scene();
    std::vector<std::string> scenes{mesh};
    for (const std::string& s : targets_sphere_scenes()) {
        scenes.push_back(s);
    }
    for (const std::string& spec : targets_layout_specs()) {
        // Grouped by tracer: each (scene, structure, methods) is built once.
        for (const std::string& scene : scenes) {
            for (const bool wt : {false, true}) {
                if (wt && scene != mesh) {
                    continue;  // the watertight row is about triangles
                }
                for (RayKind k : target_kinds) {
                    for (int threads : {1, 2}) {
                        if (threads == 2 && (wt || scene != mesh)) {
                            continue;  // scaling rows: the mesh, default methods
                        }
                        const std::string name = "targets/trace/" + spec +
                                                 (wt ? "/watertight/robust/" : "/default/plain/") +
                                                 scene + "/" + std::string(to_string(k)) +
                                                 "/threads:" + std::to_string(threads);
                        targets_timing(benchmark::RegisterBenchmark(name.c_str(), bm_trace,
                                                                    TargetsKey{scene, spec, wt}, k,
                                                                    threads)
                                           ->UseRealTime());
                    }
                    if (!wt && scene == mesh && targets_paired_layout(spec)) {
                        const std::string name = "targets/scaling/" + spec + "/" +
                                                 std::string(to_string(k)) + "/" + mesh +
                                                 "/threads:2";
                        targets_paired_timing(
                            benchmark::RegisterBenchmark(name.c_str(), bm_scaling_trace,
                                                         TargetsKey{scene, spec, wt}, k),
                            7);
                    }
                }
            }
        }
        for (int threads : {1, 2}) {
            const std::string name =
                "targets/build/" + spec + "/" + mesh + "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), bm_build, spec, mesh, threads)
                ->Unit(benchmark::kMillisecond)
                ->UseManualTime()
                ->Iterations(quick_mode() ? 1 : 5);
        }
        const std::string name = "targets/scaling/" + spec + "/build/" + mesh + "/threads:2";
        targets_paired_timing(
            benchmark::RegisterBenchmark(name.c_str(), bm_scaling_build, spec, mesh), 7);
    }
    register_targets_embree_benchmarks();
}
