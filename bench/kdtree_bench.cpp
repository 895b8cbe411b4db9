// The kd-tree's targets (`rtlab_bench --suite kdtree`; bench/report_kdtree.py makes the
// table). Every figure is taken side by side in one process, interleaved, so a loaded machine
// slows all contenders alike:
//   kdtree/trace/<scene>/<kind>: the contenders (kd_contenders(), or --accel) traced in turn on
//       the same rays, one thread, `rounds` rounds; each sample is the calling thread's CPU time
//       (so other processes on a loaded machine do not count) of enough passes over the ray set
//       to last sample_seconds().
//       Counters per contender: "<spec>|Mrays/s" (median of the rounds), "<spec>|nodes/ray" and
//       "<spec>|prims/ray" (a separate counting pass); per kd-tree row "<spec>|ratio": its
//       Mrays/s over the best binary BVH's ("bvh:" rows) of the same benchmark.
//   kdtree/build/<scene>/threads:<k>: build times of the kd-tree and binned BVH contenders from
//       the scene's triangle bounds and SceneTracer's exact triangle clip (kd-tree perfect
//       splits), TBB limited to k threads, interleaved (one thread: CPU time of the calling
//       thread, which runs the whole build; two: wall time); "<spec>|build_ms" (median) and,
//       per kd-tree row, "<spec>|build_ratio" over bvh:binned's.
// Scenes: the tessellated flake SF 3 and SF 4 with its floor (flake_meshfloor3/4) and the analytic
// flake SF 4 (flake_spheres4); --quick uses flake_meshfloor2 and flake_spheres2.
#include "accel/any_accel.h"
#include "bench/benchmarks.h"
#include "bench/trace_fixture.h"
#include "trace/clip.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace {

using namespace rtlab;
using namespace rtlab::bench;

/// The structures compared: the kd-tree with perfect splits on and off, the earlier kd-tree
/// traversal (t-value stack, one primitive id at a time) for the before/after, and the binary
/// BVHs.
std::vector<std::string> kd_contenders() {
    if (specs_named()) {
        return bench_specs();
    }
    std::vector<std::string> out;
    for (const char* s :
         {"kdtree:sah", "kdtree:sah,perfect=0", "kdtree:sah,traversal=tvalue,leaves=ids",
          "bvh:binned", "bvh:pbinned", "bvh:sweep", "bvh:pair"}) {
        out.push_back(parse_accel_spec(s).canonical());
    }
    return out;
}

bool is_binary_bvh(const std::string& spec) {
    return spec.starts_with("bvh:");
}

bool is_kdtree(const std::string& spec) {
    return spec.starts_with("kdtree");
}

/// A canonical spec without its traversal= and leaves= settings (which leave the tree alone).
std::string without_walk(const std::string& spec) {
    std::string out;
    std::size_t start = 0;
    while (start <= spec.size()) {
        const std::size_t end = std::min(spec.find(',', start), spec.size());
        const std::string part = spec.substr(start, end - start);
        if (!part.starts_with("traversal=") && !part.starts_with("leaves=")) {
            if (!out.empty()) {
                out += ',';
            }
            out += part;
        }
        start = end + 1;
    }
    return out;
}

std::vector<std::string> kd_scenes() {
    if (quick_mode()) {
        return {"flake_meshfloor2", "flake_spheres2"};
    }
    return {"flake_meshfloor3", "flake_meshfloor4", "flake_spheres4"};
}

int rounds() {
    return quick_mode() ? 3 : 7;
}

/// Least CPU time of one sample: short ray sets are traced several times per sample.
double sample_seconds() {
    return quick_mode() ? 0.01 : 0.05;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// The tracers of one scene, one per contender, kept while that scene's benchmarks run
/// (benchmarks are registered grouped by scene).
const std::vector<std::unique_ptr<SceneTracer>>& tracers(const std::string& scene) {
    static std::vector<std::unique_ptr<SceneTracer>> last;
    static std::string last_scene;
    if (last.empty() || last_scene != scene) {
        last.clear();
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        for (const std::string& spec : kd_contenders()) {
            TraceSetup setup;
            setup.accel = parse_accel_spec(spec);
            last.push_back(std::make_unique<SceneTracer>(bench_scene(scene).scene, setup));
        }
        last_scene = scene;
    }
    return last;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU seconds of the calling thread: with TBB limited to one thread the tracer runs on it, and
/// time the machine gives to other processes is not counted (this machine is shared).
double thread_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void bm_trace(benchmark::State& state, const std::string& scene, RayKind kind) {
    const std::vector<Rayf>& rays = bench_scene(scene).rays.at(kind);
    const auto& ts = tracers(scene);
    const std::vector<std::string> specs = kd_contenders();
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    TracePass tp(rays.size());
    const auto pass = [&](const SceneTracer& t, TraversalStats* st) { tp.run(t, rays, kind, st); };
    std::vector<std::vector<double>> secs(ts.size());
    std::vector<int> reps(ts.size(), 1);
    for (auto _ : state) {
        for (std::size_t i = 0; i < ts.size(); ++i) {  // warm-up; sets passes per sample
            const double t0 = thread_seconds();
            pass(*ts[i], nullptr);
            const double s = std::max(thread_seconds() - t0, 1e-6);
            reps[i] = std::max(1, static_cast<int>(sample_seconds() / s));
        }
        for (int r = 0; r < rounds(); ++r) {
            for (std::size_t i = 0; i < ts.size(); ++i) {
                const double t0 = thread_seconds();
                for (int k = 0; k < reps[i]; ++k) {
                    pass(*ts[i], nullptr);
                }
                secs[i].push_back((thread_seconds() - t0) / static_cast<double>(reps[i]));
            }
        }
    }
    const auto n = static_cast<double>(rays.size());
    double best_bvh = 0;
    std::vector<double> mrays(ts.size());
    for (std::size_t i = 0; i < ts.size(); ++i) {
        mrays[i] = n / median(secs[i]) * 1e-6;
        TraversalStats st;
        pass(*ts[i], &st);
        state.counters[specs[i] + "|Mrays/s"] = mrays[i];
        state.counters[specs[i] + "|nodes/ray"] = static_cast<double>(st.nodes) / n;
        state.counters[specs[i] + "|prims/ray"] = static_cast<double>(st.prims) / n;
        if (is_binary_bvh(specs[i])) {
            best_bvh = std::max(best_bvh, mrays[i]);
        }
    }
    for (std::size_t i = 0; i < ts.size(); ++i) {
        if (is_kdtree(specs[i]) && best_bvh > 0) {
            state.counters[specs[i] + "|ratio"] = mrays[i] / best_bvh;
        }
    }
}

void bm_build(benchmark::State& state, const std::string& scene, int threads) {
    const Scene& s = bench_scene(scene).scene;
    std::vector<Triangle<float>> tris;
    for (const MeshObject& m : s.meshes) {
        for (const auto& t : m.mesh.triangles) {
            tris.push_back(
                {m.mesh.positions[t[0]], m.mesh.positions[t[1]], m.mesh.positions[t[2]]});
        }
    }
    if (tris.empty()) {
        state.SkipWithError("no triangles");
        return;
    }
    const std::vector<Bounds3f> bounds = triangle_bounds(s);
    const ClipFn clip = [&tris](std::uint32_t i, const Bounds3f& box) {
        return clip_shape_bounds(tris[i], box);
    };
    // The kd-trees against the binned builders (the kd-tree targets' reference is bvh:binned).
    std::vector<std::string> specs;
    // traversal= and leaves= do not change the tree: one kd row per build setting.
    std::set<std::string> kd_builds;
    for (const std::string& spec : kd_contenders()) {
        if ((is_kdtree(spec) && kd_builds.insert(without_walk(spec)).second) ||
            spec.starts_with("bvh:binned") || spec.starts_with("bvh:pbinned")) {
            specs.push_back(spec);
        }
    }
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    std::vector<std::vector<double>> ms(specs.size());
    std::vector<AccelInfo> info(specs.size());
    for (auto _ : state) {
        for (int r = 0; r < (quick_mode() ? 1 : 3); ++r) {
            for (std::size_t i = 0; i < specs.size(); ++i) {
                const auto w0 = std::chrono::steady_clock::now();
                const double c0 = thread_seconds();
                AnyAccel a = build_accel(specs[i], BuildInput{bounds, clip});
                // One thread: the calling thread's CPU time; two: wall time.
                ms[i].push_back(1e3 * (threads == 1 ? thread_seconds() - c0 : seconds_since(w0)));
                info[i] = accel_info(a);
                benchmark::DoNotOptimize(a);
            }
        }
    }
    double bvh_ms = 0;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        state.counters[specs[i] + "|build_ms"] = median(ms[i]);
        state.counters[specs[i] + "|refs/prim"] = info[i].refs_per_prim;
        state.counters[specs[i] + "|sah_cost"] = info[i].sah_cost;
        if (specs[i].starts_with("bvh:binned")) {
            bvh_ms = median(ms[i]);
        }
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
        if (is_kdtree(specs[i]) && bvh_ms > 0) {
            state.counters[specs[i] + "|build_ratio"] = median(ms[i]) / bvh_ms;
        }
    }
    state.counters["prims"] = static_cast<double>(bounds.size());
}

}  // namespace

void rtlab::bench::register_kdtree_benchmarks() {
    for (const std::string& scene : kd_scenes()) {
        for (const RayKind k : bench_ray_kinds) {
            const std::string name = "kdtree/trace/" + scene + "/" + std::string(to_string(k));
            benchmark::RegisterBenchmark(name.c_str(), bm_trace, scene, k)
                ->Iterations(1)
                ->Unit(benchmark::kMillisecond);
        }
        if (scene.starts_with("flake_meshfloor")) {
            for (int threads : {1, 2}) {
                const std::string name =
                    "kdtree/build/" + scene + "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), bm_build, scene, threads)
                    ->Iterations(1)
                    ->Unit(benchmark::kMillisecond);
            }
        }
    }
}
