// batch::closest_per_ray (trace/batch.h): closest hits with each ray's own counts.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void closest_per_ray(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     std::span<TraversalStats> per_ray) {
    PerRaySink sink{per_ray};
    trace_batch(sets, robust, ClosestQuery{rays, hits}, sink);
}

}  // namespace rtlab::batch
