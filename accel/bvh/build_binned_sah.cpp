// Binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"): bins
// of equal width over the node's centroid bounds on each axis, a split between bins chosen by the
// SAH; leaf when the SAH prefers it and the range fits in max_leaf_size. A range whose centroids
// coincide (or bin_count == 1) falls back to the object median. Cost: O(N log N); subtrees in
// parallel with `threads`.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <limits>
#include <tbb/enumerable_thread_specific.h>
#include <vector>

namespace rtlab {

namespace {

/// Bin of centre c on an axis with lower centroid bound lo and scale bins/extent.
std::uint32_t bin_of(float c, float lo, float scale, std::uint32_t bins) {
    const float f = (c - lo) * scale;
    // c >= lo, so f >= 0 except for the NaN of 0 * inf (c == lo, extent so tiny that the scale
    // overflowed): both mean bin 0. The top edge (c == hi) and overflow clamp to the last bin, and
    // the float is converted only when it is in range.
    if (!(f > 0.0f)) {
        return 0;
    }
    if (!(f < static_cast<float>(bins))) {
        return bins - 1;
    }
    return std::min(bins - 1, static_cast<std::uint32_t>(f));
}

}  // namespace

Bvh build_bvh_binned_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    const std::uint32_t bins = td.config.bin_count;
    // Bin scratch, one per thread (subtrees may build concurrently).
    struct Scratch {
        std::vector<Bounds3f> bin_box;
        std::vector<std::uint32_t> bin_count;
        std::vector<float> right_area;
        std::vector<std::uint32_t> right_count;
    };
    tbb::enumerable_thread_specific<Scratch> scratch([bins] {
        return Scratch{std::vector<Bounds3f>(bins), std::vector<std::uint32_t>(bins),
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
        const Bounds3f cb = t.centroid_bounds(b, e);
        auto& [bin_box, bin_count, right_area, right_count] = scratch.local();
        // Costs are compared unnormalised (times the node area), so zero-area nodes need no
        // division: leaf = Ci * n * A, split = Ct * A + Ci * (A_L n_L + A_R n_R).
        float best = std::numeric_limits<float>::infinity();
        std::uint32_t best_axis = 0, best_bin = 0;
        for (std::uint32_t axis = 0; axis < 3; ++axis) {
            const float lo = cb.lo[axis], extent = cb.hi[axis] - cb.lo[axis];
            if (!(extent > 0.0f)) {
                continue;
            }
            const float scale = static_cast<float>(bins) / extent;
            std::fill(bin_box.begin(), bin_box.end(), Bounds3f{});
            std::fill(bin_count.begin(), bin_count.end(), 0u);
            for (std::uint32_t i = b; i < e; ++i) {
                const std::uint32_t id = t.ids[i];
                const std::uint32_t k = bin_of(t.center(id)[axis], lo, scale, bins);
                bin_box[k].extend(t.boxes[id]);
                ++bin_count[k];
            }
            // Sweep from the right, then from the left; the split after bin k puts bins [0, k]
            // left.
            Bounds3f acc;
            std::uint32_t cnt = 0;
            for (std::uint32_t k = bins - 1; k > 0; --k) {
                acc.extend(bin_box[k]);
                cnt += bin_count[k];
                right_area[k - 1] = acc.surface_area();
                right_count[k - 1] = cnt;
            }
            acc = Bounds3f{};
            cnt = 0;
            for (std::uint32_t k = 0; k + 1 < bins; ++k) {
                acc.extend(bin_box[k]);
                cnt += bin_count[k];
                if (cnt == 0 || right_count[k] == 0) {
                    continue;
                }
                const float cost = acc.surface_area() * static_cast<float>(cnt) +
                                   right_area[k] * static_cast<float>(right_count[k]);
                if (cost < best) {
                    best = cost;
                    best_axis = axis;
                    best_bin = k;
                }
            }
        }
        if (best == std::numeric_limits<float>::infinity()) {
            return n <= t.config.max_leaf_size ? std::nullopt : std::optional(t.median_split(b, e));
        }
        const float area = box.surface_area();
        const float leaf_cost = t.config.intersection_cost * static_cast<float>(n) * area;
        const float split_cost = t.config.traversal_cost * area + t.config.intersection_cost * best;
        if (n <= t.config.max_leaf_size && leaf_cost <= split_cost) {
            return std::nullopt;
        }
        const float lo = cb.lo[best_axis];
        const float scale = static_cast<float>(bins) / (cb.hi[best_axis] - lo);
        const auto first_right =
            std::partition(t.ids.begin() + b, t.ids.begin() + e, [&](std::uint32_t id) {
                return bin_of(t.center(id)[best_axis], lo, scale, bins) <= best_bin;
            });
        const auto mid = static_cast<std::uint32_t>(first_right - t.ids.begin());
        return bvh_detail::Split{mid, best_axis};
    };
    return with_threads(threads, [&] { return td.run(split, threads != 1); });
}

}  // namespace rtlab
