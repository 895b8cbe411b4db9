// Shared machinery of the BVH builders; see build_common.h.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <memory>
#include <span>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <utility>

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

namespace {

/// Keys per block of radix_pass; radix_sort_by_high sorts fewer keys by LSD passes alone.
constexpr std::size_t radix_block = std::size_t{1} << 16;

/// One stable counting pass of src into dst on the digit of digit_bits bits at `shift`, in fixed
/// blocks of radix_block keys: per-block counts (parallel), offsets digit-major then block order,
/// scatter (parallel). Returns where each digit's keys start in dst, then dst's size.
std::vector<std::uint32_t> radix_pass(std::span<const std::uint64_t> src,
                                      std::span<std::uint64_t> dst,
                                      std::uint32_t shift,
                                      std::uint32_t digit_bits) {
    const std::uint32_t radix = 1u << digit_bits;
    const std::size_t n = src.size(), blocks = (n + radix_block - 1) / radix_block;
    const auto digit = [shift, radix](std::uint64_t k) {
        return static_cast<std::uint32_t>(k >> shift) & (radix - 1);
    };
    std::vector<std::uint32_t> offset(blocks * radix);
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
        std::uint32_t* count = &offset[k * radix];
        std::fill(count, count + radix, 0u);
        for (std::size_t i = k * radix_block; i < std::min(n, (k + 1) * radix_block); ++i) {
            ++count[digit(src[i])];
        }
    });
    std::vector<std::uint32_t> start(radix + 1);
    std::uint32_t sum = 0;
    for (std::uint32_t d = 0; d < radix; ++d) {
        start[d] = sum;
        for (std::size_t k = 0; k < blocks; ++k) {
            const std::uint32_t c = offset[k * radix + d];
            offset[k * radix + d] = sum;
            sum += c;
        }
    }
    start[radix] = sum;
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
        std::uint32_t* next = &offset[k * radix];
        for (std::size_t i = k * radix_block; i < std::min(n, (k + 1) * radix_block); ++i) {
            dst[next[digit(src[i])]++] = src[i];
        }
    });
    return start;
}

/// Stable LSD radix sort of a[0, n) on `passes` digits of digit_bits (at most 11) from `shift`
/// up, on one thread, through tmp[0, n): the keys end in a after an even number of passes, else
/// in tmp.
void radix_sort_serial(std::uint64_t* a,
                       std::uint64_t* tmp,
                       std::size_t n,
                       std::uint32_t shift,
                       std::uint32_t digit_bits,
                       std::uint32_t passes) {
    const std::uint32_t radix = 1u << digit_bits;
    std::array<std::uint32_t, 2048> count;
    for (std::uint32_t p = 0; p < passes; ++p, shift += digit_bits) {
        const auto digit = [shift, radix](std::uint64_t k) {
            return static_cast<std::uint32_t>(k >> shift) & (radix - 1);
        };
        std::fill_n(count.begin(), radix, 0u);
        for (std::size_t i = 0; i < n; ++i) {
            ++count[digit(a[i])];
        }
        std::uint32_t sum = 0;
        for (std::uint32_t d = 0; d < radix; ++d) {
            sum += std::exchange(count[d], sum);
        }
        for (std::size_t i = 0; i < n; ++i) {
            tmp[count[digit(a[i])]++] = a[i];
        }
        std::swap(a, tmp);
    }
}

}  // namespace

void radix_sort_by_high(ScratchVector<std::uint64_t>& keys, std::uint32_t bits) {
    if (bits == 0) {
        return;
    }
    const std::uint32_t passes = (bits + 10) / 11, digit_bits = (bits + passes - 1) / passes;
    ScratchVector<std::uint64_t> out(keys.size());
    if (passes == 1 || keys.size() < radix_block) {
        for (std::uint32_t p = 0; p < passes; ++p) {
            radix_pass(keys, out, 32 + p * digit_bits, digit_bits);
            keys.swap(out);
        }
        return;
    }
    // The most significant digit first, in one pass over all the keys; then each of its buckets
    // by the lower digits on its own (in cache, buckets in parallel): the order of the LSD passes
    // above with one pass through memory instead of `passes`.
    const std::vector<std::uint32_t> start =
        radix_pass(keys, out, 32 + (passes - 1) * digit_bits, digit_bits);
    tbb::parallel_for(std::size_t{0}, start.size() - 1, [&](std::size_t d) {
        radix_sort_serial(out.data() + start[d], keys.data() + start[d], start[d + 1] - start[d],
                          32, digit_bits, passes - 1);
    });
    if ((passes - 1) % 2 == 0) {
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
