#pragma once
// Each suite registers its benchmarks at run time (from main, after static initialisation).

#include <string>
#include <vector>

namespace rtlab::bench {

/// True when rtlab_bench was started with --quick: suites register smaller sizes and fewer cases
/// so the whole executable finishes in under two minutes.
bool quick_mode();

/// The canonical structure specs the trace and build suites run: those named by --accel, else
/// every registry row except brute force, with default parameters.
std::vector<std::string> bench_specs();

/// True when --accel named the specs (bench_specs() is then exactly those).
bool specs_named();

/// intersect/<prim>/<method>/<precision>/<ray set>: ns per test and error rates against CGAL.
void register_intersect_benchmarks();

/// roots/<surface>/<finder>/<precision>: ns per ray and t error against an exact reference.
void register_roots_benchmarks();

/// trace/<structure>/<scene>/<ray kind>: rays/s, nodes/ray, prims/ray.
void register_trace_benchmarks();

/// build/<structure>/soup/<prims>/threads:<k>: build time, bytes/prim, SAH cost, nodes.
void register_build_benchmarks();

/// trace/embree:<quality>/... and build/embree:<quality>/...; registers nothing without Embree.
void register_embree_benchmarks();

/// targets/trace/..., targets/build/..., targets/scaling/...: the BVH layouts' target table
/// against Embree (targets_bench.cpp); only with `--suite targets`.
void register_targets_benchmarks();
/// The two-level grid's targets and the cost-model rows (bench/grid2_bench.cpp).
void register_grid2_benchmarks();

/// kdtree/trace/... and kdtree/build/...: the kd-tree's targets (kdtree_bench.cpp); only
/// with `--suite kdtree`.
void register_kdtree_benchmarks();

/// Embree's rows of the targets suite (embree_pairs.cpp); registers nothing without Embree.
void register_targets_embree_benchmarks();

/// The targets suite's scenes: the tessellated flake with its floor, and the analytic flakes.
std::string targets_mesh_scene();
std::vector<std::string> targets_sphere_scenes();

}  // namespace rtlab::bench

namespace benchmark::internal {
class Benchmark;
}

namespace rtlab {
class SceneTracer;
}

namespace rtlab::bench {

/// The targets suite's timing settings: milliseconds, repetitions reported as aggregates.
benchmark::internal::Benchmark* targets_timing(benchmark::internal::Benchmark* b);

/// The targets suite's structures: the BVH-family rows of bench_specs().
std::vector<std::string> targets_layout_specs();

/// The layouts of the suite's paired rows: the wide ones and bvh:pair (the table's best layouts).
bool targets_paired_layout(const std::string& spec);

/// The shortest timed sample of a paired row (seconds; shorter with --quick).
double targets_min_sample();

/// The settings of a paired row (targets/paired/..., paired_build/..., scaling/...): 3 repetitions
/// of `pairs` pairs (2 of 3 with --quick), reported as aggregates with min and max; manual time in
/// milliseconds.
benchmark::internal::Benchmark* targets_paired_timing(benchmark::internal::Benchmark* b, int pairs);

/// What a targets-suite tracer is built for.
struct TargetsKey {
    std::string scene;
    std::string accel;
    bool watertight = false;  ///< watertight triangle method and robust traversal
    friend bool operator==(const TargetsKey&, const TargetsKey&) = default;
};

/// The SceneTracer of key, built on first use; only the most recent key's is kept.
const SceneTracer& targets_tracer(const TargetsKey& key);

/// render/flake_mirror/{auto,all_features}: the mirror-only sphere flake rendered with the
/// auto-selected integrator instance and with every feature compiled in.
void register_render_benchmarks();

}  // namespace rtlab::bench
