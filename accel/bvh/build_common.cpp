// Shared machinery of the BVH builders; see build_common.h.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace rtlab::bvh_detail {

namespace {

/// Union of box_of(i) for i in [b, e); exact under any grouping, so the same for any threads.
template <class BoxOf>
Bounds3f union_over(std::uint32_t b, std::uint32_t e, const BoxOf& box_of) {
    const auto serial = [&](std::uint32_t lo, std::uint32_t hi, Bounds3f acc) {
        for (std::uint32_t i = lo; i < hi; ++i) {
            acc.extend(box_of(i));
        }
        return acc;
    };
    if (e - b < reduce_min) {
        return serial(b, e, Bounds3f{});
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<std::uint32_t>(b, e, reduce_block), Bounds3f{},
        [&](const tbb::blocked_range<std::uint32_t>& r, Bounds3f acc) {
            return serial(r.begin(), r.end(), acc);
        },
        [](Bounds3f x, const Bounds3f& y) {
            x.extend(y);
            return x;
        });
}

}  // namespace

std::uint32_t ceil_log2(std::uint64_t n) {
    return n <= 1 ? 0u : static_cast<std::uint32_t>(std::bit_width(n - 1));
}

Bvh::Config clamped(const Bvh::Config& cfg) {
    Bvh::Config c = cfg;
    c.max_leaf_size = std::clamp(c.max_leaf_size, 1u, BvhNode::max_prim_count);
    c.bin_count = std::max(c.bin_count, 1u);
    c.morton_bits = std::clamp(c.morton_bits, 1u, 10u);
    c.sah_block = std::clamp(c.sah_block, 1u, 64u);
    return c;
}

TopDown::TopDown(const BuildInput& in, const Bvh::Config& cfg)
    : boxes(in.bounds), centers(3 * in.bounds.size()), config(cfg) {
    const std::size_t n = boxes.size();
    const auto usable = [&](std::size_t i) { return is_usable_box(boxes[i]); };
    const std::vector<std::uint32_t> start = block_starts(n, usable);
    ids.resize(start.back());
    for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
        std::uint32_t next = start[k];
        for (std::size_t i = lo; i < hi; ++i) {
            const Vec3f c = boxes[i].center();
            for (std::size_t a = 0; a < 3; ++a) {
                centers[3 * i + a] = c[a];
            }
            if (usable(i)) {
                ids[next++] = static_cast<std::uint32_t>(i);
            }
        }
    });
}

Bounds3f TopDown::range_bounds(std::uint32_t b, std::uint32_t e) const {
    return union_over(b, e, [&](std::uint32_t i) { return boxes[ids[i]]; });
}

Bounds3f TopDown::centroid_bounds(std::uint32_t b, std::uint32_t e) const {
    return union_over(b, e, [&](std::uint32_t i) {
        const Vec3f c = center(ids[i]);
        return Bounds3f{c, c};
    });
}

Split TopDown::median_split(std::uint32_t b, std::uint32_t e) {
    const auto axis = static_cast<std::uint32_t>(centroid_bounds(b, e).largest_axis());
    const std::uint32_t mid = b + (e - b) / 2;
    std::nth_element(ids.begin() + b, ids.begin() + mid, ids.begin() + e,
                     [&](std::uint32_t x, std::uint32_t y) {
                         const float cx = center(x)[axis], cy = center(y)[axis];
                         return cx < cy || (cx == cy && x < y);
                     });
    return {mid, axis};
}

std::optional<Split> TopDown::median_or_leaf(
    TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f&, bool) {
    if (e - b <= t.config.max_leaf_size) {
        return std::nullopt;
    }
    return t.median_split(b, e);
}

void radix_sort_by_high(ScratchVector<std::uint64_t>& keys, std::uint32_t bits) {
    if (bits == 0) {
        return;
    }
    const std::uint32_t passes = (bits + 10) / 11, digit_bits = (bits + passes - 1) / passes;
    const std::uint32_t radix = 1u << digit_bits;
    constexpr std::size_t block = std::size_t{1} << 16;
    const std::size_t n = keys.size(), blocks = (n + block - 1) / block;
    ScratchVector<std::uint64_t> out(n);
    std::vector<std::uint32_t> offset(blocks * radix);
    for (std::uint32_t shift = 32; shift < 32 + bits; shift += digit_bits) {
        const auto digit = [shift, radix](std::uint64_t k) {
            return static_cast<std::uint32_t>(k >> shift) & (radix - 1);
        };
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
            std::uint32_t* count = &offset[k * radix];
            std::fill(count, count + radix, 0u);
            for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i) {
                ++count[digit(keys[i])];
            }
        });
        std::uint32_t sum = 0;
        for (std::uint32_t d = 0; d < radix; ++d) {
            for (std::size_t k = 0; k < blocks; ++k) {
                const std::uint32_t c = offset[k * radix + d];
                offset[k * radix + d] = sum;
                sum += c;
            }
        }
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
            std::uint32_t* next = &offset[k * radix];
            for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i) {
                out[next[digit(keys[i])]++] = keys[i];
            }
        });
        keys.swap(out);
    }
}

bool TopDown::must_balance(std::uint32_t depth, std::uint32_t n) {
    // An unbalanced split leaves a child of up to n - 1 primitives at depth + 1; it is safe while
    // depth + 1 + ceil_log2(n) <= 64, since a balanced split from there on loses one log2 per
    // level.
    return depth + 1 + ceil_log2(n) > 64;
}

}  // namespace rtlab::bvh_detail
