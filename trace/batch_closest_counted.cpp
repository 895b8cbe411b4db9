// batch::closest_counted and batch::closest_per_ray (trace/batch.h): closest hits with counts,
// summed per thread or kept per ray; one CountSink, so one instantiation of the loop serves both.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void closest_counted(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     TraversalStats& stats) {
    CountSink sink{&stats};
    trace_batch(sets, robust, ClosestQuery{rays, hits}, sink);
}

void closest_per_ray(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     std::span<TraversalStats> per_ray) {
    CountSink sink{nullptr, per_ray};
    trace_batch(sets, robust, ClosestQuery{rays, hits}, sink);
}

}  // namespace rtlab::batch
