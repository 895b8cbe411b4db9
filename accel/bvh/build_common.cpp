// Shared machinery of the BVH builders; see build_common.h.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace rtlab::bvh_detail {

namespace {

/// Ranges at least this long are reduced in parallel blocks of `reduce_block`: the top nodes of
/// an unbalanced tree (a floor split off a mesh) would otherwise run one thread for a whole level.
constexpr std::uint32_t reduce_min = 1u << 16;
constexpr std::uint32_t reduce_block = 1u << 14;

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
    return c;
}

TopDown::TopDown(const BuildInput& in, const Bvh::Config& cfg)
    : boxes(in.bounds), centers(in.bounds.size()), config(cfg) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boxes.size(), reduce_block),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              centers[i] = boxes[i].center();
                          }
                      });
    ids.reserve(boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
        if (is_usable_box(boxes[i])) {
            ids.push_back(i);
        }
    }
}

Bounds3f TopDown::range_bounds(std::uint32_t b, std::uint32_t e) const {
    return union_over(b, e, [&](std::uint32_t i) { return boxes[ids[i]]; });
}

Bounds3f TopDown::centroid_bounds(std::uint32_t b, std::uint32_t e) const {
    return union_over(b, e, [&](std::uint32_t i) {
        const Vec3f& c = centers[ids[i]];
        return Bounds3f{c, c};
    });
}

Split TopDown::median_split(std::uint32_t b, std::uint32_t e) {
    const auto axis = static_cast<std::uint32_t>(centroid_bounds(b, e).largest_axis());
    const std::uint32_t mid = b + (e - b) / 2;
    std::nth_element(ids.begin() + b, ids.begin() + mid, ids.begin() + e,
                     [&](std::uint32_t x, std::uint32_t y) {
                         const float cx = centers[x][axis], cy = centers[y][axis];
                         return cx < cy || (cx == cy && x < y);
                     });
    return {mid, axis};
}

void TopDown::splice(BvhNodes& nodes, std::uint32_t slot, const BvhNodes& sub) {
    const auto shift = static_cast<std::uint32_t>(nodes.size()) - 1;
    const auto moved = [shift](BvhNode node) {
        if (!node.is_leaf()) {
            node.first += shift;
        }
        return node;
    };
    nodes[slot] = moved(sub[0]);
    // In parallel blocks: the root's splice copies the whole tree, which would otherwise run on
    // one thread.
    const std::size_t base = nodes.size() - 1;
    nodes.resize(base + sub.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(1, sub.size(), reduce_block),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                              nodes[base + k] = moved(sub[k]);
                          }
                      });
}

bool TopDown::must_balance(std::uint32_t depth, std::uint32_t n) {
    // An unbalanced split leaves a child of up to n - 1 primitives at depth + 1; it is safe while
    // depth + 1 + ceil_log2(n) <= 64, since a balanced split from there on loses one log2 per
    // level.
    return depth + 1 + ceil_log2(n) > 64;
}

}  // namespace rtlab::bvh_detail
