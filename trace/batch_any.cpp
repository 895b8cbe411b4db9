// batch::any (trace/batch.h): any hit without counters.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void any(const std::vector<AnyPrimSet>& sets,
         bool robust,
         std::span<const Rayf> rays,
         std::span<std::uint32_t> blocker) {
    NoSink sink;
    trace_batch(sets, robust, AnyHitQuery{rays, blocker}, sink);
}

}  // namespace rtlab::batch
