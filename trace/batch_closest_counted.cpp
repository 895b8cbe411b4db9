// batch::closest_counted (trace/batch.h): closest hits, counts summed per thread.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void closest_counted(const std::vector<AnyPrimSet>& sets,
                     bool robust,
                     std::span<const Rayf> rays,
                     std::span<Hit> hits,
                     TraversalStats& stats) {
    BatchSink sink{&stats};
    trace_batch(sets, robust, ClosestQuery{rays, hits}, sink);
}

}  // namespace rtlab::batch
