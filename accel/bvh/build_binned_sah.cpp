// Binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"): bins
// of equal width over the node's centroid bounds on each axis, a split between bins chosen by the
// SAH; leaf when the SAH prefers it and the range fits in max_leaf_size. A range whose centroids
// coincide (or bin_count == 1) falls back to the object median. Cost: O(N log N); subtrees in
// parallel with `threads`, and the bins of large ranges (the top nodes) filled in parallel blocks.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>
#include <vector>

namespace rtlab {

namespace {

/// The bins of a range on all three axes at once (bins per axis, axis after axis): each axis's
/// lower centroid bound and scale bins / extent, 0 for an axis whose centroids coincide (all its
/// primitives then land in bin 0 and the axis is not considered).
struct AxisBins {
    std::vector<Bounds3f> box;
    std::vector<std::uint32_t> count;
    float lo[3] = {};
    float scale[3] = {};

    void clear() {
        std::fill(box.begin(), box.end(), Bounds3f{});
        std::fill(count.begin(), count.end(), 0u);
    }
    /// Adds ids[b, e) of t: one pass reading each box and centre once for the three axes.
    void add(const bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e) {
        const auto bins = static_cast<std::uint32_t>(count.size() / 3);
        for (std::uint32_t i = b; i < e; ++i) {
            const std::uint32_t id = t.ids[i];
            const Vec3f c = t.center(id);
            for (std::uint32_t axis = 0; axis < 3; ++axis) {
                const std::uint32_t k =
                    axis * bins + bvh_detail::centroid_bin(c[axis], lo[axis], scale[axis], bins);
                box[k].extend(t.boxes[id]);
                ++count[k];
            }
        }
    }
    /// Adds the bins of o (same axes and scales).
    void merge(const AxisBins& o) {
        for (std::size_t k = 0; k < count.size(); ++k) {
            box[k].extend(o.box[k]);
            count[k] += o.count[k];
        }
    }
};

/// Fills g (bins per axis already sized) with the bins of ids[b, e) over their centroid bounds;
/// ranges of bvh_detail::reduce_min or more in parallel blocks.
void bin_range(const bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, AxisBins& g) {
    const auto bins = static_cast<float>(g.count.size() / 3);
    const Bounds3f cb = t.centroid_bounds(b, e);
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
        const float extent = cb.hi[axis] - cb.lo[axis];
        g.lo[axis] = cb.lo[axis];
        g.scale[axis] = extent > 0.0f ? bins / extent : 0.0f;
    }
    g.clear();
    if (e - b < bvh_detail::reduce_min) {
        g.add(t, b, e);
        return;
    }
    // g is this thread's scratch, which a task this thread runs while it waits may reuse: the
    // empty bins are copied first, and g is only written once the reduction is done.
    const AxisBins empty = g;
    g = tbb::parallel_reduce(
        tbb::blocked_range<std::uint32_t>(b, e, bvh_detail::reduce_block), empty,
        [&](const tbb::blocked_range<std::uint32_t>& r, AxisBins acc) {
            acc.add(t, r.begin(), r.end());
            return acc;
        },
        [](AxisBins x, const AxisBins& y) {
            x.merge(y);
            return x;
        });
}

/// Bins and sweep scratch of one thread (subtrees may build concurrently).
struct BinScratch {
    AxisBins bins;
    std::vector<float> right_area;
    std::vector<std::uint32_t> right_count;
};

/// The cheapest split between bins over the three axes of g (bins per axis): its unnormalised
/// cost (times the node area, so zero-area nodes need no division), axis and last left bin; cost
/// infinity when no split leaves both sides non-empty.
struct BinSplit {
    float cost = std::numeric_limits<float>::infinity();
    std::uint32_t axis = 0;
    std::uint32_t bin = 0;
};

BinSplit best_bin_split(const Bvh::Config& cfg, std::uint32_t bins, BinScratch& s) {
    const AxisBins& g = s.bins;
    BinSplit best;
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
        if (g.scale[axis] == 0.0f) {
            continue;
        }
        const Bounds3f* bin_box = &g.box[axis * bins];
        const std::uint32_t* bin_count = &g.count[axis * bins];
        // Sweep from the right, then from the left; the split after bin k puts bins [0, k] left.
        Bounds3f acc;
        std::uint32_t cnt = 0;
        for (std::uint32_t k = bins - 1; k > 0; --k) {
            acc.extend(bin_box[k]);
            cnt += bin_count[k];
            s.right_area[k - 1] = acc.surface_area();
            s.right_count[k - 1] = cnt;
        }
        acc = Bounds3f{};
        cnt = 0;
        for (std::uint32_t k = 0; k + 1 < bins; ++k) {
            acc.extend(bin_box[k]);
            cnt += bin_count[k];
            if (cnt == 0 || s.right_count[k] == 0) {
                continue;
            }
            const float cost = acc.surface_area() * bvh_detail::sah_count(cfg, cnt) +
                               s.right_area[k] * bvh_detail::sah_count(cfg, s.right_count[k]);
            if (cost < best.cost) {
                best = {cost, axis, k};
            }
        }
    }
    return best;
}

}  // namespace

Bvh build_bvh_binned_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    const std::uint32_t bins = td.config.bin_count;
    tbb::enumerable_thread_specific<BinScratch> scratch([bins] {
        return BinScratch{
            AxisBins{std::vector<Bounds3f>(3 * bins), std::vector<std::uint32_t>(3 * bins)},
            std::vector<float>(bins), std::vector<std::uint32_t>(bins)};
    });

    auto split = [&](bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f& box,
                     bool balance) -> std::optional<bvh_detail::Split> {
        const std::uint32_t n = e - b;
        if (!balance && bvh_detail::sah_leaf_anyway(t.config, n)) {
            return std::nullopt;
        }
        if (balance || bins < 2) {
            return n <= t.config.max_leaf_size ? std::nullopt : std::optional(t.median_split(b, e));
        }
        BinScratch& local = scratch.local();
        bin_range(t, b, e, local.bins);
        const BinSplit best = best_bin_split(t.config, bins, local);
        if (best.cost == std::numeric_limits<float>::infinity()) {
            return n <= t.config.max_leaf_size ? std::nullopt : std::optional(t.median_split(b, e));
        }
        // Leaf = Ci * n * A, split = Ct * A + Ci * (A_L n_L + A_R n_R), both times the area.
        const float area = box.surface_area();
        const float leaf_cost =
            t.config.intersection_cost * bvh_detail::sah_count(t.config, n) * area;
        const float split_cost =
            t.config.traversal_cost * area + t.config.intersection_cost * best.cost;
        if (n <= t.config.max_leaf_size && leaf_cost <= split_cost) {
            return std::nullopt;
        }
        const float lo = local.bins.lo[best.axis], scale = local.bins.scale[best.axis];
        const auto first_right =
            std::partition(t.ids.begin() + b, t.ids.begin() + e, [&](std::uint32_t id) {
                return bvh_detail::centroid_bin(t.center(id)[best.axis], lo, scale, bins) <=
                       best.bin;
            });
        const auto mid = static_cast<std::uint32_t>(first_right - t.ids.begin());
        return bvh_detail::Split{mid, best.axis};
    };
    return with_threads(threads, [&] { return td.run(split, threads != 1); });
}

}  // namespace rtlab
