#pragma once
// Each suite registers its benchmarks at run time (from main, after static initialisation).

namespace rtlab::bench {

/// intersect/triangle/<method>/<precision>: ns per ray-triangle test.
void register_intersect_benchmarks();

/// trace/<structure>/<scene>/<ray kind>: rays/s, nodes/ray, prims/ray.
void register_trace_benchmarks();

}  // namespace rtlab::bench
