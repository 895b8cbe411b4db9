#pragma once
// SceneTracer's batch entry points (internal to trace/), one translation unit per query and sink
// (trace/batch_*.cpp): every set in order, its rays in parallel with TBB, its method and
// structure static. Each ray is independent, so results do not depend on the thread count.

#include "accel/accel.h"
#include "intersect/hit.h"
#include "trace/prim_sets.h"

#include <cstdint>
#include <span>
#include <vector>

namespace rtlab::batch {

/// Closest hits; hits[] starts as misses. Throws for a method without hit points.
void closest(const std::vector<AnyPrimSet>& sets,
             bool robust,
             std::span<const Rayf> rays,
             std::span<Hit> hits);
/// closest(), adding every ray's traversal counts to stats (per-thread sums).
void closest_counted(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     TraversalStats& stats);
/// closest(), adding ray i's own counts to per_ray[i].
void closest_per_ray(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     std::span<TraversalStats> per_ray);
/// Any hit; blocker[] starts as invalid_id.
void any(const std::vector<AnyPrimSet>& sets,
         bool robust,
         std::span<const Rayf> rays,
         std::span<std::uint32_t> blocker);
/// any(), adding every ray's traversal counts to stats.
void any_counted(const std::vector<AnyPrimSet>& sets,
                 bool robust,
                 std::span<const Rayf> rays,
                 std::span<std::uint32_t> blocker,
                 TraversalStats& stats);

}  // namespace rtlab::batch
