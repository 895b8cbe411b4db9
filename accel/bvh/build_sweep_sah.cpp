// Full-sweep SAH (MacDonald & Booth 1990, "Heuristics for ray tracing using space subdivision"):
// every split between consecutive centroids on every axis is evaluated with the SAH. The ids are
// sorted once per axis (ties by id; a parallel radix sort) and kept sorted by stable
// partitioning, so the build is O(N) per tree level after the sorts; subtrees in parallel with
// `threads`, and the sweeps and partitions of large ranges (the top nodes) in parallel blocks.
// Ranges whose centroids coincide split at the median by count.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <tbb/parallel_for.h>
#include <vector>

namespace rtlab {

namespace {

/// The SAH's best split of one axis order o[b, e): its unnormalised cost (times the node area,
/// as in the binned builder) and the first slot of the right child, the first minimum in slot
/// order; cost infinity when no split has a finite cost. right_area[b, e) is scratch.
struct AxisBest {
    float cost = std::numeric_limits<float>::infinity();
    std::uint32_t mid = 0;
};

AxisBest sweep_axis(const bvh_detail::TopDown& t,
                    std::span<const std::uint32_t> o,
                    std::uint32_t b,
                    std::uint32_t e,
                    std::span<float> right_area) {
    // Slots [lo, hi) given the union of o[hi, e) (right) and of o[b, lo) (left): sweep from the
    // right, then from the left; the split before slot i puts o[b, i) left.
    const auto sweep = [&](std::uint32_t lo, std::uint32_t hi, Bounds3f right, Bounds3f left) {
        for (std::uint32_t i = hi; i-- > lo;) {
            right.extend(t.boxes[o[i]]);
            right_area[i] = right.surface_area();
        }
        AxisBest best;
        for (std::uint32_t i = lo; i < hi; ++i) {
            if (i > b) {
                const float cost = left.surface_area() * bvh_detail::sah_count(t.config, i - b) +
                                   right_area[i] * bvh_detail::sah_count(t.config, e - i);
                if (cost < best.cost) {
                    best = {cost, i};
                }
            }
            left.extend(t.boxes[o[i]]);
        }
        return best;
    };
    if (e - b < bvh_detail::reduce_min) {
        return sweep(b, e, Bounds3f{}, Bounds3f{});
    }
    // Large ranges (the top of the tree) in parallel blocks, each starting from the unions of
    // the blocks beside it. Unions are exact under any grouping, so every area, cost and the
    // first minimum are those of the serial sweep.
    const std::size_t n = e - b;
    const std::size_t blocks = (n + bvh_detail::reduce_block - 1) / bvh_detail::reduce_block;
    std::vector<Bounds3f> block_box(blocks), after(blocks + 1), before(blocks + 1);
    bvh_detail::for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
        for (std::size_t i = b + lo; i < b + hi; ++i) {
            block_box[k].extend(t.boxes[o[i]]);
        }
    });
    for (std::size_t k = 0; k < blocks; ++k) {
        before[k + 1] = Bounds3f(before[k]).extend(block_box[k]);
        after[blocks - 1 - k] = Bounds3f(after[blocks - k]).extend(block_box[blocks - 1 - k]);
    }
    std::vector<AxisBest> best(blocks);
    bvh_detail::for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
        best[k] = sweep(static_cast<std::uint32_t>(b + lo), static_cast<std::uint32_t>(b + hi),
                        after[k + 1], before[k]);
    });
    AxisBest out;
    for (const AxisBest& x : best) {
        if (x.cost < out.cost) {
            out = x;
        }
    }
    return out;
}

/// The sweep builder's state over one TopDown: the ids sorted by centre on each axis (every
/// node's range [b, e) holds the same id set in all three orders) and scratch indexed by slot or
/// id, so concurrent subtrees (disjoint ranges) never share it. Uninitialised (ScratchVector):
/// every entry is written before it is read.
class SweepOrders {
public:
    explicit SweepOrders(const bvh_detail::TopDown& td)
        : right_area_(td.ids.size()), goes_left_(td.boxes.size()), scratch_(td.ids.size()) {
        sort(td);
    }

    /// TopDown's split callback: a leaf (nullopt), the median of the largest centroid axis when
    /// balancing or when the centroids coincide, else the cheapest sweep split over the axes.
    std::optional<bvh_detail::Split> split(bvh_detail::TopDown& t,
                                           std::uint32_t b,
                                           std::uint32_t e,
                                           const Bounds3f& box,
                                           bool balance) {
        const std::uint32_t n = e - b;
        if (!balance && bvh_detail::sah_leaf_anyway(t.config, n)) {
            return std::nullopt;
        }
        std::uint32_t best_axis = 0, best_mid = 0;
        const Bounds3f cb = t.centroid_bounds(b, e);
        // Coinciding centroids give no geometric order to sweep (only the id tie-break): such a
        // range becomes a leaf if it fits, else splits at the median by count.
        const bool coincide = cb.lo == cb.hi;
        if (coincide && n <= t.config.max_leaf_size) {
            return std::nullopt;
        }
        if (balance || coincide) {
            best_axis = static_cast<std::uint32_t>(cb.largest_axis());
            best_mid = b + n / 2;
        } else {
            float best = std::numeric_limits<float>::infinity();
            for (std::uint32_t a = 0; a < 3; ++a) {
                const AxisBest x = sweep_axis(t, order_[a], b, e, right_area_);
                if (x.cost < best) {
                    best = x.cost;
                    best_axis = a;
                    best_mid = x.mid;
                }
            }
            if (best == std::numeric_limits<float>::infinity()) {
                // Only overflowing areas get here: split at the middle of the x order.
                best_axis = 0;
                best_mid = b + n / 2;
            }
            const float area = box.surface_area();
            const float leaf_cost =
                t.config.intersection_cost * bvh_detail::sah_count(t.config, n) * area;
            const float split_cost =
                t.config.traversal_cost * area + t.config.intersection_cost * best;
            if (n <= t.config.max_leaf_size && leaf_cost <= split_cost) {
                return std::nullopt;
            }
        }
        partition(t, b, e, best_axis, best_mid);
        return bvh_detail::Split{best_mid, best_axis};
    }

private:
    /// order_[a]: the ids sorted by centre on axis a (ties by id), as 64-bit keys, the centre's
    /// bits made to order as unsigned integers above the id (ids are in increasing order in
    /// td.ids, so the stable radix sort breaks ties by id): the same strict total order as
    /// comparing centres.
    void sort(const bvh_detail::TopDown& td) {
        const std::size_t n_all = td.ids.size();
        ScratchVector<std::uint64_t> keys(n_all);
        for (std::uint32_t a = 0; a < 3; ++a) {
            tbb::parallel_for(std::size_t{0}, n_all, [&](std::size_t i) {
                keys[i] =
                    (std::uint64_t{bvh_detail::float_order_key(td.center(td.ids[i])[a])} << 32) |
                    td.ids[i];
            });
            bvh_detail::radix_sort_by_high(keys, 32);
            order_[a].resize(n_all);
            tbb::parallel_for(std::size_t{0}, n_all, [&](std::size_t i) {
                order_[a][i] = static_cast<std::uint32_t>(keys[i]);
            });
        }
    }

    /// Splits [b, e) at slot mid of the axis order: marks the left set, stably partitions the
    /// other two orders so they stay sorted, and copies the axis order into t.ids.
    void partition(bvh_detail::TopDown& t,
                   std::uint32_t b,
                   std::uint32_t e,
                   std::uint32_t axis,
                   std::uint32_t mid) {
        const std::uint32_t n = e - b;
        const ScratchVector<std::uint32_t>& split_order = order_[axis];
        bvh_detail::for_range(n, [&](std::size_t lo, std::size_t hi) {
            for (std::size_t i = b + lo; i < b + hi; ++i) {
                goes_left_[split_order[i]] = i < mid ? 1 : 0;
            }
        });
        for (std::uint32_t a = 0; a < 3; ++a) {
            if (a != axis) {
                bvh_detail::stable_partition(order_[a], scratch_, b, e,
                                             [&](std::uint32_t id) { return goes_left_[id] != 0; });
            }
        }
        bvh_detail::for_range(n, [&](std::size_t lo, std::size_t hi) {
            std::copy(split_order.begin() + b + lo, split_order.begin() + b + hi,
                      t.ids.begin() + b + lo);
        });
    }

    std::array<ScratchVector<std::uint32_t>, 3> order_;
    ScratchVector<float> right_area_;
    ScratchVector<char> goes_left_;
    ScratchVector<std::uint32_t> scratch_;
};

Bvh build(const BuildInput& in, const Bvh::Config& cfg, bool parallel) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    SweepOrders orders(td);
    return td.run([&](bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f& box,
                      bool balance) { return orders.split(t, b, e, box, balance); },
                  parallel);
}

}  // namespace

Bvh build_bvh_sweep_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    return with_threads(threads, [&] { return build(in, cfg, threads != 1); });
}

}  // namespace rtlab
