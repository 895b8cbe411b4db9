// batch::any_counted (trace/batch.h): any hit, counts summed per thread.
#include "trace/batch_loop.h"

namespace rtlab::batch {

void any_counted(const std::vector<AnyPrimSet>& sets,
                 bool robust,
                 std::span<const Rayf> rays,
                 std::span<std::uint32_t> blocker,
                 TraversalStats& stats) {
    CountSink sink{&stats};
    trace_batch(sets, robust, AnyHitQuery{rays, blocker}, sink);
}

}  // namespace rtlab::batch
