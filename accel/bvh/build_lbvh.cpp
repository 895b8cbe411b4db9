// LBVH (Lauterbach et al. 2009) with the radix-tree split of Karras 2012, "Maximizing parallelism
// in the construction of BVHs, octrees, and k-d trees": 30-bit Morton codes of the centres
// (morton_bits per axis over the centroid bounds), sorted (ties by id); a node splits where its
// highest differing code bit flips, runs of equal codes split at their middle. This variant walks
// the same tree top-down (subtrees in parallel with `threads`) and stops at max_leaf_size; node
// boxes are filled in bottom-up (a refit: each primitive box read once). Cost: O(N log N) for the
// sort (a parallel LSD radix sort on the codes) and the searches.

#include "accel/bvh/build_common.h"
#include "base/scratch_vector.h"

#include <algorithm>
#include <bit>
#include <tbb/parallel_for.h>
#include <vector>

namespace rtlab {

namespace {

/// Spreads the low 10 bits of v so that bit i moves to bit 3i.
std::uint32_t spread_bits(std::uint32_t v) {
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

/// Cell of centre coordinate c on an axis of lower bound lo and `cells / extent` scale.
std::uint32_t quantize(float c, float lo, float scale, std::uint32_t cells) {
    const float f = (c - lo) * scale;
    if (!(f > 0.0f)) {
        return 0;  // also the NaN of 0 * inf when a tiny extent overflowed the scale
    }
    if (!(f < static_cast<float>(cells))) {
        return cells - 1;
    }
    return std::min(cells - 1, static_cast<std::uint32_t>(f));
}

Bvh build(const BuildInput& in, const Bvh::Config& cfg, bool parallel) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    const Bounds3f cb = td.centroid_bounds(0, static_cast<std::uint32_t>(td.ids.size()));
    const std::uint32_t cells = 1u << td.config.morton_bits;
    float scale[3];
    for (std::size_t a = 0; a < 3; ++a) {
        const float extent = cb.hi[a] - cb.lo[a];
        scale[a] = extent > 0.0f ? static_cast<float>(cells) / extent : 0.0f;
    }
    // Code layout: bit 3i + 2 is x, 3i + 1 is y, 3i is z of quantised bit i.
    // Keys are unique (the id is in the low half) and made in id order, so the stable radix sort
    // on the code gives the order of sorting the whole keys.
    ScratchVector<std::uint64_t> keys(td.ids.size());
    tbb::parallel_for(std::size_t{0}, keys.size(), [&](std::size_t i) {
        const Vec3f c = td.center(td.ids[i]);
        const std::uint32_t code = (spread_bits(quantize(c.x, cb.lo.x, scale[0], cells)) << 2) |
                                   (spread_bits(quantize(c.y, cb.lo.y, scale[1], cells)) << 1) |
                                   spread_bits(quantize(c.z, cb.lo.z, scale[2], cells));
        keys[i] = (static_cast<std::uint64_t>(code) << 32) | td.ids[i];
    });
    bvh_detail::radix_sort_by_high(keys, 3 * td.config.morton_bits);
    ScratchVector<std::uint32_t> codes(keys.size());
    tbb::parallel_for(std::size_t{0}, keys.size(), [&](std::size_t i) {
        codes[i] = static_cast<std::uint32_t>(keys[i] >> 32);
        td.ids[i] = static_cast<std::uint32_t>(keys[i] & 0xFFFFFFFFu);
    });

    auto split = [&](bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f&,
                     bool balance) -> std::optional<bvh_detail::Split> {
        const std::uint32_t n = e - b;
        if (n <= t.config.max_leaf_size) {
            return std::nullopt;
        }
        const std::uint32_t diff = codes[b] ^ codes[e - 1];
        if (balance || diff == 0) {
            const auto axis = static_cast<std::uint32_t>(t.centroid_bounds(b, e).largest_axis());
            return bvh_detail::Split{b + n / 2, axis};
        }
        // Codes in [b, e) share every bit above the highest differing one, so the ones with that
        // bit set form a suffix: find its start by binary search.
        const auto bit = static_cast<std::uint32_t>(std::bit_width(diff) - 1);
        const std::uint32_t mask = 1u << bit;
        const auto first_set = std::partition_point(
            codes.begin() + b, codes.begin() + e, [&](std::uint32_t c) { return (c & mask) == 0; });
        const auto mid = static_cast<std::uint32_t>(first_set - codes.begin());
        return bvh_detail::Split{mid, 2 - bit % 3};
    };
    return td.run<bvh_detail::NodeBoxes::after_split>(split, parallel);
}

}  // namespace

Bvh build_bvh_lbvh(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    return with_threads(threads, [&] { return build(in, cfg, threads != 1); });
}

}  // namespace rtlab
