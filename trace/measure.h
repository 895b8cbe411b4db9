#pragma once
// Timing one ray batch through a prepared scene, the one way `rtlab trace` and `rtlab sweep` do
// it: K timed runs (median reported), then an optional separate counting pass so counting never
// perturbs the timing.

#include "intersect/hit.h"
#include "intersect/ray.h"
#include "trace/scene_tracer.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rtlab {

/// What to measure.
struct MeasureOptions {
    bool any_hit = false;  ///< occlusion queries instead of closest hit
    int repeat = 1;        ///< timed runs; the median is reported
    int warmup = 0;        ///< untimed runs first (thread pool start-up, caches, page faults)
    bool stats = false;    ///< add a counting pass (nodes and primitive tests per ray)
    bool epo = false;      ///< with stats: also the end-point overlap of BVHs over triangles
    /// Closest hit only: also time the traversal alone (SceneTracer::traverse), repeat runs.
    bool leaf_time = false;
};

/// The figures of one measured batch.
struct TraceMeasurement {
    std::size_t rays = 0;
    std::size_t hits = 0;               ///< rays with a hit (occluded rays with any_hit)
    double build_ms = 0;                ///< the tracer's build time
    double trace_ms = 0;                ///< median of the timed runs
    std::vector<double> trace_ms_runs;  ///< every timed run, in order
    double mrays_per_s = 0;             ///< rays / trace_ms
    std::uint64_t accel_bytes = 0;      ///< memory of all sets' structures
    double bytes_per_prim = 0;          ///< accel_bytes / primitive count
    std::uint64_t nodes = 0;            ///< nodes over all sets' structures
    std::uint64_t leaves = 0;           ///< leaves over all sets' structures
    std::uint32_t max_depth = 0;        ///< deepest leaf over all sets
    double sah_cost = 0;                ///< the structures' own cost-model values, summed over sets
    bool has_stats = false;             ///< nodes_per_ray and prims_per_ray are set
    double nodes_per_ray = 0;
    double prims_per_ray = 0;
    /// With stats: the one cost model (accel/cost_model.h) with the spec's ct and ci, summed over
    /// sets: predicted ct * nodes + ci * prims per ray, and the same over the counted figures.
    double cost_model = 0;
    double measured_cost = 0;
    double epo = -1;  ///< with epo: end-point overlap of the triangle set's BVH (-1: none)
    /// With leaf_time: median time of the traversal alone, windows ending at the hits found
    /// (-1: not measured); trace_ms less this is about the leaf work.
    double traverse_ms = -1;
};

/// Median of v (the mean of the middle two for an even count); 0 for an empty v.
double median_of(std::vector<double> v);

/// Traces `rays` opt.repeat times and reports the median time and the structure figures; with
/// opt.stats a separate counting pass adds nodes_per_ray and prims_per_ray. When `hits` is given
/// it receives the hits of the last timed run (any_hit: t = 0 and the blocker's id for an
/// occluded ray). Exceptions of the tracer (e.g. a method that cannot report hit points) pass on.
TraceMeasurement measure_trace(const SceneTracer& tracer,
                               std::span<const Rayf> rays,
                               const MeasureOptions& opt,
                               std::vector<Hit>* hits = nullptr);

}  // namespace rtlab
