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

/// issue12/trace/... and issue12/build/...: issue 12's target table (issue12_bench.cpp); only
/// with `--suite issue12`.
void register_issue12_benchmarks();
/// Issue 16's two-level grid targets and cost-model rows (bench/grid2_bench.cpp).
void register_grid2_benchmarks();

/// kdtree/trace/... and kdtree/build/...: issue 16's kd-tree targets (kdtree_bench.cpp); only
/// with `--suite kdtree`.
void register_kdtree_benchmarks();

/// Embree's rows of the issue-12 suite (embree_issue12.cpp); registers nothing without Embree.
void register_issue12_embree_benchmarks();

/// The issue-12 suite's scenes: the tessellated flake with its floor, and the analytic flakes.
std::string issue12_mesh_scene();
std::vector<std::string> issue12_sphere_scenes();

}  // namespace rtlab::bench

namespace benchmark::internal {
class Benchmark;
}

namespace rtlab {
class SceneTracer;
}

namespace rtlab::bench {

/// The issue-12 suite's timing settings: milliseconds, repetitions reported as aggregates.
benchmark::internal::Benchmark* issue12_timing(benchmark::internal::Benchmark* b);

/// The issue-12 suite's structures: the BVH-family rows of bench_specs().
std::vector<std::string> issue12_layout_specs();

/// The layouts of the suite's paired rows: the wide ones and bvh:pair (the table's best layouts).
bool issue12_paired_layout(const std::string& spec);

/// The shortest timed sample of a paired row (seconds; shorter with --quick).
double issue12_min_sample();

/// The settings of a paired row (issue12/paired/..., paired_build/..., scaling/...): 3 repetitions
/// of `pairs` pairs (2 of 3 with --quick), reported as aggregates with min and max; manual time in
/// milliseconds.
benchmark::internal::Benchmark* issue12_paired_timing(benchmark::internal::Benchmark* b, int pairs);

/// What an issue-12 tracer is built for.
struct Issue12Key {
    std::string scene;
    std::string accel;
    bool watertight = false;  ///< watertight triangle method and robust traversal
    friend bool operator==(const Issue12Key&, const Issue12Key&) = default;
};

/// The SceneTracer of key, built on first use; only the most recent key's is kept.
const SceneTracer& issue12_tracer(const Issue12Key& key);

/// render/flake_mirror/{auto,all_features}: the mirror-only sphere flake rendered with the
/// auto-selected integrator instance and with every feature compiled in.
void register_render_benchmarks();

}  // namespace rtlab::bench
