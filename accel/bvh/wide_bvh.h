#pragma once
// Wide BVHs (BVH4, BVH8, BVH16) collapsed from any binary build (accel/bvh/wide_collapse.cpp): each
// wide node pulls up the grandchildren of largest surface area until it holds N children, so the
// nodes most rays reach are opened first (SAH-aware collapse as in Embree's BVH4/8 builders).
// Traversal clips the ray against all N child boxes with one SIMD slab test (accel/bvh/
// wide_kernels.h, compiled for SSE2, AVX2 and AVX-512 and chosen per call by base/simd.h), visits
// the hit children near to far by entry distance, skips popped entries beyond the shrunk tmax and
// stops at the first any-hit. Leaf slots index prim_ids in the binary build's leaf order. A BVH8
// may carry quantised copies of its nodes (quantize_bvh8, the bvh8q row), which traversal reads.

#include "accel/accel.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/wide_kernels.h"
#include "accel/bvh/wide_node.h"
#include "base/large_pages.h"
#include "base/simd.h"

#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace rtlab {

/// A BVH with N (4, 8 or 16) children per node; nodes[0] is the root (holding the binary root's
/// children, or the binary root itself when that is a leaf).
template <unsigned N>
struct WideBvh {
    static constexpr unsigned width = N;

    LargeVector<WideNode<N>> nodes;  ///< root at 0; empty when no box was usable
    /// BVH8 only, empty unless quantised (quantize_bvh8): nodes quantised one for one, which
    /// traversal then reads instead of `nodes` (kept for bounds, info and validate).
    LargeVector<QWideNode8> qnodes;
    /// Empty, or one per node (add_diag_bounds, `bounds=dop14`): each slot's extents along
    /// diag_dirs, which plain traversal clips to as well as to the boxes.
    LargeVector<WideDiag<N>> diags;
    std::vector<std::uint32_t> prim_ids;   ///< leaf slots -> caller's primitive ids
    std::uint32_t prim_count = 0;          ///< number of input boxes (ids are < prim_count)
    std::uint32_t unreferenced_count = 0;  ///< input boxes left out (empty, NaN or infinite)
    Bvh::Config config;                    ///< the source binary build's configuration

    /// Closest hit: offers hit_fn every primitive of every leaf whose box the shrinking window
    /// meets, nearer children first. Invalid rays return false before any node.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return dispatch<false, IsRobust, false>(ray, hit_fn, stats);
    }

    /// Closest hit offering whole leaves: leaf_fn(first, count, ray) tests the primitives of
    /// prim_ids slots [first, first + count) (in slot order, as intersect would offer them one by
    /// one), shrinks ray.tmax on a hit and returns true. For leaf data stored in slot order.
    template <bool IsRobust = false, LeafRangeFn<Rayf> F, StatsSink S = NoStats>
    bool intersect_leaves(Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        return dispatch<false, IsRobust, true>(ray, leaf_fn, stats);
    }

    /// Any hit offering whole leaves: the first leaf_fn(first, count, ray) returning true ends it.
    template <bool IsRobust = false, LeafRangeFn<const Rayf> F, StatsSink S = NoStats>
    bool occluded_leaves(const Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        return dispatch<true, IsRobust, true>(ray, leaf_fn, stats);
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return dispatch<true, IsRobust, false>(ray, hit_fn, stats);
    }

    /// The union of the root's child boxes (empty when no box was usable).
    Bounds3f bounds() const;

    /// Sizes, depth and the SAH cost sum(wide node A * Ct) + sum(leaf A * n * Ci) over A(root)
    /// with the source build's Ct and Ci (a wide node visit counted as one node visit).
    AccelInfo info() const;

    /// Empty when every invariant holds (each usable primitive referenced once, leaves of at
    /// most max_leaf_size primitives covering every slot but padding slots, occupied slots first
    /// with non-empty boxes, every child box inside its parent slot's box, inner nodes other than
    /// the root with at least two children, every node reached once, depth <= 64, and any
    /// quantised nodes one per node with the same children and enclosing boxes); else the first
    /// violation.
    std::string validate() const;

    friend bool operator==(const WideBvh&, const WideBvh&) = default;

    /// f(view) with what traversal reads (the quantised nodes when there are any), after the
    /// checks every query starts with; `none` for an invalid ray (not counted) or an empty
    /// structure (counted as a ray).
    template <class T, StatsSink S, class F>
    T visit(const Rayf& ray, S& stats, T none, F&& f) const {
        if (!is_valid(ray)) {
            return none;
        }
        stats.count_ray();
        if (nodes.empty()) {
            return none;
        }
        return visit_view(f);
    }

    /// f(view) with what traversal reads (the quantised nodes when there are any), for callers
    /// that check their rays themselves (a block of rays); nodes must not be empty.
    template <class F>
    decltype(auto) visit_view(F&& f) const {
        if constexpr (N == 8) {
            if (!qnodes.empty()) {
                return f(view_of(qnodes));
            }
        }
        return f(view_of(nodes));
    }

private:
    /// validate()'s part for qnodes: one per node, the same children, boxes enclosing theirs.
    std::string validate_quantized() const;
    /// validate()'s part for diags: none or one per node, empty slots empty, occupied ones
    /// non-empty and enclosing their child node's slots (accel/bvh/wide_diag.cpp).
    std::string validate_diags() const;

    template <class Node>
    WideViewOf<Node> view_of(const LargeVector<Node>& ns) const {
        const WideDiag<N>* d = nullptr;
        if constexpr (std::is_same_v<Node, WideNode<N>>) {
            d = diags.empty() ? nullptr : diags.data();
        }
        return {ns.data(), prim_ids.data(), ns.size() * sizeof(Node) >= prefetch_min_bytes, d};
    }

    template <bool IsAnyHit, bool IsRobust, bool ByRange, class R, class F, class S>
    bool dispatch(R& ray, F& hit_fn, S& stats) const {
        return visit(ray, stats, false, [&](const auto& view) {
            switch (simd_level()) {
            case SimdLevel::avx512:
                return simd_avx512::wide_traverse<IsAnyHit, IsRobust, ByRange>(view, ray, hit_fn,
                                                                               stats);
            case SimdLevel::avx2:
                return simd_avx2::wide_traverse<IsAnyHit, IsRobust, ByRange>(view, ray, hit_fn,
                                                                             stats);
            case SimdLevel::sse2:
                break;
            }
            return simd_sse2::wide_traverse<IsAnyHit, IsRobust, ByRange>(view, ray, hit_fn, stats);
        });
    }
};

/// Which binary nodes become the wide nodes (accel/bvh/wide_collapse.cpp). `greedy` opens, from a
/// node's two children on, the inner child of largest surface area until there are N children or
/// only leaves. `sah` chooses them all at once so that the summed surface area of the wide nodes
/// (the SAH's expected node visits of a random ray; the leaves are the source tree's either way)
/// is the least any collapse of the source tree reaches (dynamic programming over the binary
/// tree, Ylitie, Karras & Laine 2017, section 4.1, without their leaf merging).
enum class WideCollapse { greedy, sah };

/// BVH4, BVH8 and BVH16 from a binary BVH (accel/bvh/wide_collapse.cpp); taken by value so that a
/// build's temporary source gives up its prim_ids instead of having them copied.
template <unsigned N>
WideBvh<N> collapse_bvh(Bvh binary,
                        ChildOrder order = ChildOrder::area,
                        WideCollapse rule = WideCollapse::sah);

/// The BVH8 of collapse_bvh<8>(binary, order, rule) with its nodes quantised (qnodes; accel/bvh/
/// wide_quantize.cpp): traversal reads 128-byte nodes instead of 256-byte ones.
WideBvh<8> quantize_bvh8(Bvh binary,
                         ChildOrder order = ChildOrder::area,
                         WideCollapse rule = WideCollapse::sah);

/// Fills w.diags: every slot's extents along diag_dirs, from in.extent per primitive (or the
/// primitive boxes' corners without it) for leaf slots and from the child node's slots for inner
/// ones (accel/bvh/wide_diag.cpp). `in` is the input w was built from.
template <unsigned N>
void add_diag_bounds(WideBvh<N>& w, const BuildInput& in);

/// True for WideBvh<N>.
template <class A>
inline constexpr bool is_wide_bvh = false;
template <unsigned N>
inline constexpr bool is_wide_bvh<WideBvh<N>> = true;

extern template struct WideBvh<4>;
extern template struct WideBvh<8>;
extern template struct WideBvh<16>;

static_assert(Accel<WideBvh<4>>);
static_assert(Accel<WideBvh<8>>);
static_assert(Accel<WideBvh<16>>);
static_assert(LeafRangeAccel<WideBvh<4>> && LeafRangeAccel<WideBvh<8>> &&
              LeafRangeAccel<WideBvh<16>>);

}  // namespace rtlab
