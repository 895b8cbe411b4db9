// batch::closest (trace/batch.h): closest hits without counters.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void closest(const std::vector<AnyPrimSet>& sets,
             bool robust,
             std::span<const Rayf> rays,
             std::span<Hit> hits) {
    NoSink sink;
    trace_batch(sets, robust, ClosestQuery{rays, hits}, sink);
}

}  // namespace rtlab::batch
