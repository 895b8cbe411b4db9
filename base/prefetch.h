#pragma once
// A software prefetch that the optimiser keeps, and the structure size from which traversals use
// it.

#include <cstddef>

namespace rtlab {

/// Structures whose nodes take at least this many bytes prefetch children during traversal; below
/// it the nodes stay in the L2 cache and the prefetches only cost instructions. Measured on bvh8,
/// one thread: on a 2-core Intel Xeon VM (2 MiB L2) sphere flakes SF 4 (132 KB) -6% and SF 5
/// (1.2 MB) -1% with prefetching, the tessellated SF 3 (3.4 MB) +2-4% and SF 4 (1.65M triangles)
/// +14-22%; on a 2-core AMD EPYC VM (1 MiB L2) SF 5 +2-4%, SF 4 -2-5% when always on.
inline constexpr std::size_t prefetch_min_bytes = std::size_t{1} << 20;

/// Starts fetching the cache line holding p into all cache levels (x86 prefetcht0; a hint: no
/// fault for any address). An asm statement rather than __builtin_prefetch: GCC 12 deletes a
/// loop whose only statements are __builtin_prefetch calls (it assumes such a loop ends,
/// -ffinite-loops, and then finds that it computes nothing).
inline void prefetch_line(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
    asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
    __builtin_prefetch(p);
#endif
}

}  // namespace rtlab
