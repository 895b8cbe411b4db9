// parallel_blocks (trace/batch_loop.h): TBB's parallel_for compiled once for every batch unit.
#include "trace/batch_loop.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rtlab::batch {

void parallel_blocks(std::size_t n, FunctionRef<void(std::size_t, std::size_t)> body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace rtlab::batch
