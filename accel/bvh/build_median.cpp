// Object-median BVH (the "equal counts" split of Kay & Kajiya 1986 style hierarchies, pbrt's
// EqualCounts): split at the median centroid on the largest centroid axis until a range fits in
// one leaf; node boxes filled in bottom-up. Cost: O(N log N) with nth_element; subtrees in
// parallel with `threads`.

#include "accel/bvh/build_common.h"

namespace rtlab {

Bvh build_bvh_median(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    return with_threads(threads, [&] {
        return td.run<bvh_detail::NodeBoxes::after_split>(bvh_detail::TopDown::median_or_leaf,
                                                          threads != 1);
    });
}

}  // namespace rtlab
