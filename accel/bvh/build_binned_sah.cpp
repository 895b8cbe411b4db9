// Binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"): bins
// of equal width over the node's centroid bounds on each axis, a split between bins chosen by the
// SAH; leaf when the SAH prefers it and the range fits in max_leaf_size. A range whose centroids
// coincide (or bin_count == 1) falls back to the object median. Cost: O(N log N); subtrees in
// parallel with `threads`, and the bins of large ranges (the top nodes) filled in parallel blocks.
// The bins, sweep and partition are the binning module's (accel/bvh/binning.h) over Bounds3f.

#include "accel/bvh/binning.h"
#include "accel/bvh/build_common.h"

#include <algorithm>
#include <limits>
#include <tbb/enumerable_thread_specific.h>
#include <vector>

namespace rtlab {

namespace {

using Bins = binning::Bins<Bounds3f>;

/// One thread's object bins of a range (subtrees may build concurrently) with each axis's lower
/// centroid bound and scale bins / extent, 0 for an axis whose centroids coincide (all its
/// primitives then land in bin 0 and the axis is not considered).
struct AxisBins {
    Bins bins;
    float lo[3] = {};
    float scale[3] = {};
};

/// Fills g with the bins of ids[b, e) over their centroid bounds: one pass reading each box and
/// centre once for the three axes; ranges of bvh_detail::reduce_min or more in parallel blocks.
void bin_range(const bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, AxisBins& g) {
    // g is this thread's scratch, which a task this thread runs while it waits may reuse: the
    // scales are local until the bins are done.
    const std::uint32_t nb = g.bins.count;
    const Bounds3f cb = t.centroid_bounds(b, e);
    float lo[3], scale[3];
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
        const float extent = cb.hi[axis] - cb.lo[axis];
        lo[axis] = cb.lo[axis];
        scale[axis] = extent > 0.0f ? static_cast<float>(nb) / extent : 0.0f;
    }
    g.bins.reset(nb, false);
    binning::reduce_blocks(e - b, g.bins, [&](Bins& acc, std::size_t first, std::size_t end) {
        for (std::size_t i = b + first; i < b + end; ++i) {
            const std::uint32_t id = t.ids[i];
            const Vec3f c = t.center(id);
            for (std::uint32_t axis = 0; axis < 3; ++axis) {
                const std::uint32_t k =
                    axis * nb + bvh_detail::centroid_bin(c[axis], lo[axis], scale[axis], nb);
                acc.box[k].extend(t.boxes[id]);
                ++acc.enter[k];
            }
        }
    });
    std::copy(lo, lo + 3, g.lo);
    std::copy(scale, scale + 3, g.scale);
}

}  // namespace

Bvh build_bvh_binned_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    bvh_detail::TopDown td(in, bvh_detail::clamped(cfg));
    const std::uint32_t bins = td.config.bin_count;
    tbb::enumerable_thread_specific<AxisBins> scratch(
        [bins] { return AxisBins{Bins(bins, false)}; });

    auto split = [&](bvh_detail::TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f& box,
                     bool balance) -> std::optional<bvh_detail::Split> {
        const std::uint32_t n = e - b;
        if (!balance && bvh_detail::sah_leaf_anyway(t.config, n)) {
            return std::nullopt;
        }
        if (balance || bins < 2) {
            return n <= t.config.max_leaf_size ? std::nullopt : std::optional(t.median_split(b, e));
        }
        AxisBins& local = scratch.local();
        bin_range(t, b, e, local);
        binning::BinSplit<Bounds3f> best;
        for (std::uint32_t axis = 0; axis < 3; ++axis) {
            if (local.scale[axis] != 0.0f) {
                binning::sweep(
                    local.bins, axis, [](const Bounds3f& x) { return x.surface_area(); },
                    [&](std::uint32_t c) { return bvh_detail::sah_count(t.config, c); }, best);
            }
        }
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
        const float lo = local.lo[best.axis], scale = local.scale[best.axis];
        const std::uint32_t* first_right = binning::partition(
            t.ids.data() + b, t.ids.data() + e,
            [&](std::uint32_t id) {
                return bvh_detail::centroid_bin(t.center(id)[best.axis], lo, scale, bins) <=
                       best.bin;
            },
            [](std::uint32_t, bool) {});
        const auto mid = static_cast<std::uint32_t>(first_right - t.ids.data());
        return bvh_detail::Split{mid, best.axis};
    };
    return with_threads(threads, [&] { return td.run(split, threads != 1); });
}

}  // namespace rtlab
