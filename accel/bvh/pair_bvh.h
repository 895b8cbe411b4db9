#pragma once
// Binary BVH with both children's boxes stored in their parent (a 64-byte node, SoA per axis as
// tinybvh's BVH_SoA and Embree's BVH4 node keep them), converted from any built Bvh, the child of
// larger surface area first (ChildOrder::area). Traversal tests both boxes with one SSE slab
// test, descends into the hit child on the ray's side of the split (the ray's direction sign on
// the split axis, as pbrt's dirIsNeg: no wait for the distances) and pushes the other only when
// it is hit, with its entry distance, so a closest-hit ray skips it on pop once a nearer hit is
// found; any-hit takes child 0 first (the larger box: its next node is known before the box test
// ends) and stops at the first blocker. The robust mode widens distances
// exactly as clip_slabs<true> (intersect/box/slabs.h; Ize 2013), and NaN distances (origin on a
// face plane, zero direction) leave the interval unchanged as there. Cost per ray: O(log N) nodes
// for well-built trees; one box test per child, as Bvh.

#include "accel/accel.h"
#include "accel/bvh/bvh.h"
#include "base/large_pages.h"
#include "base/prefetch.h"
#include "intersect/box/slabs.h"

#include <cassert>
#include <cstdint>
#include <string>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rtlab {

/// An inner node with its two children's boxes: x = (lo0, lo1, hi0, hi1) of child 0 and 1, the
/// same for y and z; a child is an inner node (count 0, child = node index) or a leaf (count > 0,
/// child = first slot in prim_ids). The source node's split axis rides in count[0]'s top two bits,
/// and count[1]'s bit 30 is set when child 0 is the split's upper side.
struct alignas(64) PairNode {
    static constexpr std::uint32_t count_mask = (1u << 30) - 1;
    float x[4];
    float y[4];
    float z[4];
    std::uint32_t child[2];
    std::uint32_t count[2];

    /// Child c's primitive count (0: an inner node).
    std::uint32_t count_of(int c) const { return count[c] & count_mask; }
    /// The axis the source tree split this node on.
    std::uint32_t axis() const { return count[0] >> 30; }
    /// 1 when child 0 is the upper side of the split (the source's second child), else 0.
    std::uint32_t flipped() const { return count[1] >> 30; }

    /// Child c's box.
    Bounds3f child_bounds(int c) const {
        return {{x[c], y[c], z[c]}, {x[2 + c], y[2 + c], z[2 + c]}};
    }
    friend bool operator==(const PairNode&, const PairNode&) = default;
};

static_assert(sizeof(PairNode) == 64, "PairNode fills one cache line");

/// A binary BVH of PairNodes; leaves and primitive order as the source Bvh.
struct PairBvh {
    LargeVector<PairNode> nodes;           ///< inner nodes; nodes[0] is the root when it is inner
    std::vector<std::uint32_t> prim_ids;   ///< leaf slots -> caller's primitive ids
    Bounds3f root_box;                     ///< the root's box (empty when no box was usable)
    std::uint32_t root_child = 0;          ///< root: 0 (inner) or its first slot (leaf)
    std::uint32_t root_count = 0;          ///< root: 0 (inner) or its primitive count (leaf)
    std::uint32_t prim_count = 0;          ///< number of input boxes
    std::uint32_t unreferenced_count = 0;  ///< input boxes left out (empty, NaN or infinite)
    Bvh::Config config;                    ///< the source binary build's configuration

    /// The same tree as b, in pair nodes with their children in `order`; b by value, so that a
    /// build's temporary source gives up its prim_ids instead of having them copied.
    static PairBvh convert(Bvh b, ChildOrder order = ChildOrder::area);

    /// Closest hit: offers hit_fn every primitive in a leaf whose box the shrinking window meets,
    /// the child on the ray's side of the split first. Invalid rays return false before any node.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return traverse<false, IsRobust, false>(ray, hit_fn, stats);
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return traverse<true, IsRobust, false>(ray, hit_fn, stats);
    }

    /// Closest hit offering whole leaves: leaf_fn(first, count, ray) tests the primitives of
    /// prim_ids slots [first, first + count), shrinks ray.tmax on a hit and returns true (for
    /// leaf data stored in slot order: no id indirection while tracing).
    template <bool IsRobust = false, LeafRangeFn<Rayf> F, StatsSink S = NoStats>
    bool intersect_leaves(Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        return traverse<false, IsRobust, true>(ray, leaf_fn, stats);
    }

    /// Any hit offering whole leaves: the first leaf_fn(first, count, ray) returning true ends it.
    template <bool IsRobust = false, LeafRangeFn<const Rayf> F, StatsSink S = NoStats>
    bool occluded_leaves(const Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        return traverse<true, IsRobust, true>(ray, leaf_fn, stats);
    }

    /// The root box.
    Bounds3f bounds() const { return root_box; }

    /// Sizes (nodes: pair nodes; bytes: nodes and ids), depth and the SAH cost with the source's
    /// costs (the source Bvh's value: same tree, same boxes).
    AccelInfo info() const;

    /// Empty when every invariant holds (each usable primitive in exactly one leaf, children
    /// inside their parent's box, leaves of at most config.max_leaf_size, depth <= 64, every node
    /// reached once); else the first violation.
    std::string validate() const;

    friend bool operator==(const PairBvh&, const PairBvh&) = default;

private:
    struct Entry {
        std::uint32_t child;
        std::uint32_t count;
        float t;  ///< entry distance of its box
    };

    /// Both children's boxes against the window [tmin, tmax]: bit c of the result is set when
    /// child c is hit, tn[c] receives its entry distance.
    template <bool IsRobust>
    static int test(
        const PairNode& n, const SlabRay<float>& sr, float tmin, float tmax, float tn[2]);

    // hit_fn takes one primitive id (ByRange false) or a whole leaf as (first slot, count). One
    // function on purpose, as wide_traverse_as: a leaf step shared with the other traversals
    // measured 3-8% slower on the tessellated SF 4's shadow rays (`rtlab trace --threads 1
    // --repeat 9`, 4 alternating rounds). When both children are hit, any hit takes child 0 (the
    // larger box) first, as the wide traversal; closest hit the ray's side of the split, as many
    // nodes per ray as distance order on the tessellated SF 4 and faster (primary rays 2-7% in 6
    // of 7 rounds of `rtlab trace --threads 1 --repeat 9`); taking the side for any hit too cost
    // 3% against child 0.
    template <bool IsAnyHit, bool IsRobust, bool ByRange, class R, class F, class S>
    bool traverse(R& ray, F& hit_fn, S& stats) const {
        if (!bvh_detail::count_if_valid(ray, stats) || prim_ids.empty()) {
            return false;
        }
        const SlabRay<float> sr(ray);
        float t0 = ray.tmin, t1 = ray.tmax;
        stats.count_node();
        if (!clip_slabs<IsRobust>(root_box.lo, root_box.hi, sr, t0, t1)) {
            return false;
        }
        const bool prefetch = nodes.size() * sizeof(PairNode) >= prefetch_min_bytes;
        // Bit a set when the ray runs towards -a: the split's upper child is then the nearer.
        const unsigned neg = (sr.neg[0] ? 1u : 0u) | (sr.neg[1] ? 2u : 0u) | (sr.neg[2] ? 4u : 0u);
        Entry stack[64];
        std::uint32_t size = 0;
        Entry cur{root_child, root_count, t0};
        bool hit = false;
        for (;;) {
            if (cur.count == 0) {
                const PairNode& n = nodes[cur.child];
                stats.count_node();
                stats.count_node();
                // Fetch the inner children while their boxes are tested: the next node's load
                // is the traversal's longest wait on large scenes.
                const std::uint32_t count[2] = {n.count_of(0), n.count_of(1)};
                for (int c = 0; c < 2; ++c) {
                    if (prefetch && count[c] == 0) {
                        prefetch_line(&nodes[n.child[c]]);
                    }
                }
                float tn[2];
                const int mask = test<IsRobust>(n, sr, ray.tmin, ray.tmax, tn);
                if (mask == 3) {
                    // Both hit: the near child as said above the function.
                    const int near =
                        IsAnyHit ? 0 : static_cast<int>(((neg >> n.axis()) ^ n.flipped()) & 1u);
                    assert(size < 64 && "depth > 64: the builders guarantee depth <= 64");
                    stack[size++] = {n.child[1 - near], count[1 - near], tn[1 - near]};
                    cur = {n.child[near], count[near], tn[near]};
                    continue;
                }
                if (mask != 0) {
                    const int c = mask >> 1;
                    cur = {n.child[c], count[c], tn[c]};
                    continue;
                }
            } else if constexpr (ByRange) {
                stats.count_prims(cur.count);
                if constexpr (IsAnyHit) {
                    if (hit_fn(cur.child, cur.count, ray)) {
                        return true;
                    }
                } else {
                    hit = hit_fn(cur.child, cur.count, ray) || hit;
                }
            } else {
                const std::uint32_t end = cur.child + cur.count;
                for (std::uint32_t i = cur.child; i < end; ++i) {
                    stats.count_prim();
                    if constexpr (IsAnyHit) {
                        if (hit_fn(prim_ids[i], ray)) {
                            return true;
                        }
                    } else {
                        hit = hit_fn(prim_ids[i], ray) || hit;
                    }
                }
            }
            // Pop; a closest-hit ray skips entries whose box starts beyond its current window.
            for (;;) {
                if (size == 0) {
                    return hit;
                }
                cur = stack[--size];
                if (IsAnyHit || !(cur.t > ray.tmax)) {
                    break;
                }
            }
        }
    }
};

#if defined(__SSE2__)
template <bool IsRobust>
inline int PairBvh::test(
    const PairNode& n, const SlabRay<float>& sr, float tmin, float tmax, float tn[2]) {
    // Lanes hold (lo0, lo1, hi0, hi1) distances; swapping the halves gives (hi, lo), and the
    // ray's direction sign per axis picks which half is the near one for both children at once.
    const auto select = [](__m128 mask, __m128 a, __m128 b) {
#if defined(__SSE4_1__)
        return _mm_blendv_ps(b, a, mask);
#else
        return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
#endif
    };
    const __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
    const __m128 none = _mm_setzero_ps();
    __m128 t0 = _mm_set1_ps(tmin);
    __m128 t1 = _mm_set1_ps(tmax);
    const float* planes[3] = {n.x, n.y, n.z};
    for (int a = 0; a < 3; ++a) {
        const __m128 t = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(planes[a]), _mm_set1_ps(sr.org[a])),
                                    _mm_set1_ps(sr.inv_dir[a]));
        const __m128 swapped = _mm_shuffle_ps(t, t, _MM_SHUFFLE(1, 0, 3, 2));
        const __m128 neg = sr.neg[a] ? all : none;
        __m128 near_t = select(neg, swapped, t);
        __m128 far_t = select(neg, t, swapped);
        if constexpr (IsRobust) {
            // As clip_slabs<true>: widen both outward by 2*gamma(3), sign-aware.
            const __m128 grow = _mm_set1_ps(slab_grow<float>);
            const __m128 shrink = _mm_set1_ps(slab_shrink<float>);
            near_t = _mm_mul_ps(near_t, select(_mm_cmpgt_ps(near_t, none), shrink, grow));
            far_t = _mm_mul_ps(far_t, select(_mm_cmpgt_ps(far_t, none), grow, shrink));
        }
        // max_ps(a, b) is a > b ? a : b, so a NaN distance keeps the interval (clip_slabs).
        t0 = _mm_max_ps(near_t, t0);
        t1 = _mm_min_ps(far_t, t1);
    }
    tn[0] = _mm_cvtss_f32(t0);
    tn[1] = _mm_cvtss_f32(_mm_shuffle_ps(t0, t0, _MM_SHUFFLE(1, 1, 1, 1)));
    return _mm_movemask_ps(_mm_cmple_ps(t0, t1)) & 3;
}
#else
template <bool IsRobust>
inline int PairBvh::test(
    const PairNode& n, const SlabRay<float>& sr, float tmin, float tmax, float tn[2]) {
    int mask = 0;
    for (int c = 0; c < 2; ++c) {
        const Bounds3f b = n.child_bounds(c);
        float t0 = tmin, t1 = tmax;
        if (clip_slabs<IsRobust>(b.lo, b.hi, sr, t0, t1)) {
            mask |= 1 << c;
            tn[c] = t0;
        }
    }
    return mask;
}
#endif

static_assert(Accel<PairBvh>);
static_assert(LeafRangeAccel<PairBvh>);

}  // namespace rtlab
