// Full-sweep SAH (MacDonald & Booth 1990, "Heuristics for ray tracing using space subdivision"):
// every split between consecutive centroids on every axis is evaluated with the SAH. The ids are
// sorted once per axis (ties by id) and kept sorted by stable partitioning, so the build is
// O(N log N) for the sort plus O(N) per tree level; subtrees in parallel with `threads`. Ranges
// whose centroids coincide split at the median by count.

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <array>
#include <limits>
#include <tbb/parallel_sort.h>
#include <vector>

namespace rtlab {

namespace {

Bvh build(const BuildInput& in, const Bvh::Config& cfg, bool parallel) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    const std::size_t n_all = td.ids.size();
    // order[a] holds the ids sorted by centre on axis a; every node's range [b, e) holds the same
    // id set in all three arrays.
    std::array<std::vector<std::uint32_t>, 3> order;
    // One axis after the other, each sort itself parallel: three sorts side by side leave one of
    // two threads idle for the third. The order is a strict total order, so the result is unique.
    for (std::uint32_t a = 0; a < 3; ++a) {
        order[a] = td.ids;
        tbb::parallel_sort(order[a].begin(), order[a].end(), [&](std::uint32_t x, std::uint32_t y) {
            const float cx = td.center(x)[a], cy = td.center(y)[a];
            return cx < cy || (cx == cy && x < y);
        });
    }
    // Scratch indexed by slot or id, so concurrent subtrees (disjoint ranges) never share it.
    std::vector<float> right_area(n_all);
    std::vector<char> goes_left(td.boxes.size(), 0);
    std::vector<std::uint32_t> scratch(n_all);

    auto split = [&](bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f& box,
                     bool balance) -> std::optional<bvh_detail::Split> {
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
            // Costs compared unnormalised (times the node area), as in the binned builder.
            float best = std::numeric_limits<float>::infinity();
            for (std::uint32_t a = 0; a < 3; ++a) {
                const std::vector<std::uint32_t>& o = order[a];
                Bounds3f acc;
                for (std::uint32_t i = e - 1; i > b; --i) {
                    acc.extend(t.boxes[o[i]]);
                    right_area[i] = acc.surface_area();
                }
                acc = Bounds3f{};
                for (std::uint32_t i = b + 1; i < e; ++i) {
                    acc.extend(t.boxes[o[i - 1]]);
                    const float cost = acc.surface_area() * static_cast<float>(i - b) +
                                       right_area[i] * static_cast<float>(e - i);
                    if (cost < best) {
                        best = cost;
                        best_axis = a;
                        best_mid = i;
                    }
                }
            }
            if (best == std::numeric_limits<float>::infinity()) {
                // Only overflowing areas get here: split at the middle of the x order.
                best_axis = 0;
                best_mid = b + n / 2;
            }
            const float area = box.surface_area();
            const float leaf_cost = t.config.intersection_cost * static_cast<float>(n) * area;
            const float split_cost =
                t.config.traversal_cost * area + t.config.intersection_cost * best;
            if (n <= t.config.max_leaf_size && leaf_cost <= split_cost) {
                return std::nullopt;
            }
        }
        // Mark the left set, then stably partition the other two orders so they stay sorted.
        for (std::uint32_t i = b; i < e; ++i) {
            goes_left[order[best_axis][i]] = i < best_mid ? 1 : 0;
        }
        for (std::uint32_t a = 0; a < 3; ++a) {
            if (a == best_axis) {
                continue;
            }
            std::vector<std::uint32_t>& o = order[a];
            std::uint32_t l = b, r = b;
            for (std::uint32_t i = b; i < e; ++i) {
                if (goes_left[o[i]]) {
                    o[l++] = o[i];
                } else {
                    scratch[r++] = o[i];
                }
            }
            std::copy(scratch.begin() + b, scratch.begin() + r, o.begin() + l);
        }
        std::copy(order[best_axis].begin() + b, order[best_axis].begin() + e, t.ids.begin() + b);
        return bvh_detail::Split{best_mid, best_axis};
    };
    return td.run(split, parallel);
}

}  // namespace

Bvh build_bvh_sweep_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    return with_threads(threads, [&] { return build(in, cfg, threads != 1); });
}

}  // namespace rtlab
