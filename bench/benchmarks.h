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

/// render/flake_mirror/{auto,all_features}: the mirror-only sphere flake rendered with the
/// auto-selected integrator instance and with every feature compiled in.
void register_render_benchmarks();

}  // namespace rtlab::bench
