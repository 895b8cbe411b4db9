#pragma once
// The binning module of the binned BVH builders (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies"; spatial bins as in Stich et al. 2009, "Spatial Splits in Bounding
// Volume Hierarchies"): per-axis bins of boxes and counts, filled in fixed blocks, one SAH sweep
// over them and the in-place partition. Generic over the box type and its area so each builder
// keeps its arithmetic (Bounds3f surface areas, or binned::Box half areas in SSE).

#include "accel/bvh/build_common.h"

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace rtlab::binning {

/// The bins of all three axes, `count` per axis, axis after axis: each bin's box, how many
/// references enter it and (spatial bins) how many leave it. An object bin holds a reference whole
/// and counts it in `enter` only; a spatial bin holds the parts of the references spanning it,
/// counted in `enter` at their first bin and in `leave` at their last.
template <class Box>
struct Bins {
    std::uint32_t count = 0;
    std::vector<Box> box;
    std::vector<std::uint32_t> enter, leave;

    Bins() = default;
    /// Empty bins, n per axis, with `leave` counts when `spatial`.
    Bins(std::uint32_t n, bool spatial) { reset(n, spatial); }
    /// Empties the bins and sizes them to n per axis (reusing the storage).
    void reset(std::uint32_t n, bool spatial) {
        count = n;
        box.assign(3 * std::size_t{n}, Box{});
        enter.assign(3 * std::size_t{n}, 0);
        leave.assign(spatial ? 3 * std::size_t{n} : 0, 0);
    }
    /// Adds the bins of o (same sizes).
    void merge(const Bins& o) {
        for (std::size_t k = 0; k < box.size(); ++k) {
            box[k].extend(o.box[k]);
            enter[k] += o.enter[k];
        }
        for (std::size_t k = 0; k < leave.size(); ++k) {
            leave[k] += o.leave[k];
        }
    }
    /// References entering bins [0, split] of `axis`: those a split after bin `split` puts left.
    std::uint32_t left_of(std::uint32_t axis, std::uint32_t split) const {
        std::uint32_t c = 0;
        for (std::uint32_t k = 0; k <= split; ++k) {
            c += enter[axis * count + k];
        }
        return c;
    }
};

/// The cheapest split found so far: unnormalised SAH cost (sum of area times counted primitives,
/// so nodes of zero area need no division), its axis, its last left bin and the children's boxes;
/// cost infinity while none leaves both sides non-empty.
template <class Box>
struct BinSplit {
    float cost = std::numeric_limits<float>::infinity();
    std::uint32_t axis = 0;
    std::uint32_t bin = 0;
    Box left, right;
};

/// Sweeps the planes between the bins of `axis` of g by the SAH, area(box) * count(n) per side,
/// and keeps a cheaper one in best (ties keep the earlier axis, then bin). A split after bin k
/// puts the references entering bins [0, k] left and those leaving bins (k, end) right. Object
/// bins test only the planes after a non-empty bin: the planes up to the next one split the same
/// references at the same cost, and the first of them is that one, so the answer is the one of
/// testing every plane.
template <class Box, class Area, class Count>
void sweep(const Bins<Box>& g,
           std::uint32_t axis,
           const Area& area,
           const Count& count,
           BinSplit<Box>& best) {
    thread_local std::vector<std::uint32_t> at;  // the bins to sweep, in order
    thread_local std::vector<Box> right_box;     // union of the bins after at[p]
    thread_local std::vector<std::uint32_t> right_count;
    thread_local std::vector<float> right_cost;  // area(right_box[p]) * count(right_count[p])
    const std::uint32_t nb = g.count;
    const bool spatial = !g.leave.empty();
    const Box* box = &g.box[axis * nb];
    const std::uint32_t* enter = &g.enter[axis * nb];
    const std::uint32_t* leave = spatial ? &g.leave[axis * nb] : enter;
    at.resize(nb);
    right_box.resize(nb);
    right_count.resize(nb);
    right_cost.resize(nb);
    std::uint32_t m = 0;
    for (std::uint32_t k = 0; k < nb; ++k) {
        at[m] = k;
        m += spatial || enter[k] != 0 ? 1 : 0;
    }
    Box acc;
    std::uint32_t cnt = 0;
    for (std::uint32_t p = m; p-- > 1;) {
        acc.extend(box[at[p]]);
        cnt += leave[at[p]];
        right_box[p - 1] = acc;
        right_count[p - 1] = cnt;
        right_cost[p - 1] = area(acc) * count(cnt);
    }
    acc = Box{};
    cnt = 0;
    for (std::uint32_t p = 0; p + 1 < m; ++p) {
        acc.extend(box[at[p]]);
        cnt += enter[at[p]];
        if (cnt == 0 || right_count[p] == 0) {
            continue;
        }
        const float cost = area(acc) * count(cnt) + right_cost[p];
        if (cost < best.cost) {
            best = {cost, axis, at[p], acc, right_box[p]};
        }
    }
}

/// Fills acc (empty on entry) by add(acc, lo, hi) over [0, n): at once for n < reduce_min, else
/// one copy of it per block of bvh_detail::for_blocks filled in parallel, merged in block order
/// (kept in *blocks when given). acc is written only at the end, so it may be scratch that a task
/// this thread runs while it waits reuses. The same result for any thread count.
template <class T, class Add>
void reduce_blocks(std::size_t n, T& acc, const Add& add, std::vector<T>* blocks = nullptr) {
    if (n < bvh_detail::reduce_min) {
        add(acc, 0, n);
        return;
    }
    std::vector<T> own;
    std::vector<T>& part = blocks != nullptr ? *blocks : own;
    part.assign((n + bvh_detail::reduce_block - 1) / bvh_detail::reduce_block, acc);
    bvh_detail::for_blocks(
        n, [&](std::size_t k, std::size_t lo, std::size_t hi) { add(part[k], lo, hi); });
    T sum = part[0];
    for (std::size_t k = 1; k < part.size(); ++k) {
        sum.merge(part[k]);
    }
    acc = std::move(sum);
}

/// Moves the elements of [first, last) with goes_left to the front by swapping misplaced pairs
/// from both ends (the order std::partition gives), calling seen(x, left) once for every element
/// where it ends; returns the first element of the right part.
template <class T, class Pred, class Seen>
T* partition(T* first, T* last, const Pred& goes_left, const Seen& seen) {
    for (;;) {
        while (first < last && goes_left(*first)) {
            seen(*first++, true);
        }
        while (first < last && !goes_left(last[-1])) {
            seen(*--last, false);
        }
        if (first >= last) {
            return first;
        }
        std::swap(*first, last[-1]);
        seen(*first++, true);
        seen(*--last, false);
    }
}

}  // namespace rtlab::binning
