#pragma once
// The `threads` parameter of every parallel builder: run the build on that many TBB threads.

#include <cstdint>
#include <tbb/task_arena.h>

namespace rtlab {

/// f() on `threads` TBB threads; 0 runs it where it is called (all the threads TBB allows there).
template <class F>
auto with_threads(std::uint32_t threads, F&& f) {
    if (threads == 0) {
        return f();
    }
    tbb::task_arena arena(static_cast<int>(threads));
    return arena.execute(f);
}

}  // namespace rtlab
