#pragma once
// Binary BVH over primitive boxes: 32-byte Wald nodes with adjacent children, built by one of the
// builders in accel/bvh/build_*.cpp (one free function each, listed in accel/registry.cpp),
// traversed front-to-back by the ray's direction sign on each node's split axis with a fixed
// 64-entry stack. Cost per ray: O(log N) nodes for well-built trees. Boxes that fail is_usable_box
// (accel/accel.h) are never referenced; validate() counts them as legal gaps.

#include "accel/accel.h"
#include "accel/bvh/node.h"
#include "base/large_pages.h"
#include "intersect/box/slabs.h"

#include <cassert>
#include <cstdint>
#include <string>
#include <vector>

namespace rtlab {

/// A binary BVH's nodes: in huge pages once 2 MiB or more (base/large_pages.h), as bvh:pair's.
using BvhNodes = LargeVector<BvhNode>;

namespace bvh_detail {

/// The start of the binary traversals (Bvh, PairBvh): counts ray when it is valid (is_valid) and
/// returns true; an invalid ray is not counted and reaches no node.
template <class S>
[[gnu::always_inline]] inline bool count_if_valid(const Rayf& ray, S& stats) {
    if (!is_valid(ray)) {
        return false;
    }
    stats.count_ray();
    return true;
}

}  // namespace bvh_detail

/// A binary BVH: the root at 0, then child pairs in the order a depth-first build splits their
/// parents (a left subtree's pairs precede its right sibling's), and the leaves' primitive ids.
struct Bvh {
    /// Build parameters; the builders clamp out-of-range values and store the clamped ones.
    struct Config {
        std::uint32_t max_leaf_size = 4;  ///< leaves never hold more (clamped to [1, 2^30 - 1])
        std::uint32_t bin_count = 16;     ///< bins per axis for binned SAH (>= 1; 1 = median)
        float traversal_cost = 1.0f;      ///< SAH cost of one node visit
        float intersection_cost = 1.0f;   ///< SAH cost of one primitive test
        std::uint32_t morton_bits = 10;   ///< LBVH bits per axis (clamped to [1, 10]; 30-bit codes)
        std::uint32_t sah_block = 1;      ///< SAH counts primitives in blocks of this many

        friend bool operator==(const Config&, const Config&) = default;
    };

    BvhNodes nodes;                        ///< root at 0; empty when no box was usable
    std::vector<std::uint32_t> prim_ids;   ///< leaf slots -> caller's primitive ids
    std::uint32_t prim_count = 0;          ///< number of input boxes (ids are < prim_count)
    std::uint32_t unreferenced_count = 0;  ///< input boxes left out (empty, NaN or infinite)
    Config config;                         ///< the (clamped) configuration it was built with

    /// Closest hit: offers hit_fn every primitive in a leaf whose box the shrinking window
    /// [ray.tmin, ray.tmax] meets, near child first. Invalid rays return false before any node.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return traverse<false, IsRobust>(ray, hit_fn, stats);
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking. Invalid rays return
    /// false before any node.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return traverse<true, IsRobust>(ray, hit_fn, stats);
    }

    /// The root box (empty when no box was usable).
    Bounds3f bounds() const { return nodes.empty() ? Bounds3f{} : nodes[0].bounds(); }

    /// Sizes, depth and the SAH cost sum(inner A * Ct) + sum(leaf A * n * Ci), divided by the
    /// root area A(root) (Ci * N when the root has zero area), with the Config's Ct and Ci.
    AccelInfo info() const;

    /// Empty when every invariant holds (each usable primitive referenced, at most once per
    /// leaf: bvh:sbvh may put one in several leaves; ids < prim_count, children inside their
    /// parent, non-empty leaves of at most max_leaf_size primitives covering every slot but
    /// padding slots, depth <= 64, every node reachable once); else the first violation.
    std::string validate() const;

    friend bool operator==(const Bvh&, const Bvh&) = default;

private:
    /// The one traversal loop behind intersect (IsAnyHit false: R is Rayf, hit_fn shrinks
    /// ray.tmax, all hits are collected) and occluded (IsAnyHit true: R is const Rayf, the
    /// first hit ends it). Nodes are clipped against the current window, near child first.
    template <bool IsAnyHit, bool IsRobust, class R, class F, class S>
    bool traverse(R& ray, F& hit_fn, S& stats) const {
        if (!bvh_detail::count_if_valid(ray, stats) || nodes.empty()) {
            return false;
        }
        const SlabRay<float> sr(ray);
        std::uint32_t stack[64];
        std::uint32_t size = 0;
        std::uint32_t current = 0;
        bool hit = false;
        for (;;) {
            const BvhNode& node = nodes[current];
            stats.count_node();
            float t0 = ray.tmin, t1 = ray.tmax;
            if (clip_slabs<IsRobust>(node.lo, node.hi, sr, t0, t1)) {
                if (!node.is_leaf()) {
                    // Near child first: with a negative direction on the split axis the right
                    // (higher) child is met first.
                    const bool right_first = sr.neg[node.axis()];
                    assert(size < 64 && "depth > 64: the builders guarantee depth <= 64");
                    stack[size++] = right_first ? node.first : node.first + 1;
                    current = right_first ? node.first + 1 : node.first;
                    continue;
                }
                const std::uint32_t end = node.first + node.prim_count();
                for (std::uint32_t i = node.first; i < end; ++i) {
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
            if (size == 0) {
                return hit;
            }
            current = stack[--size];
        }
    }
};

static_assert(Accel<Bvh>);

/// How a layout converted from a Bvh (bvh:pair, bvh4, bvh8, bvh8q) orders a node's children:
/// `area` puts the larger surface areas first, which any-hit traversal, visiting children in slot
/// order, reaches first (they hold the most geometry; bvh:pair shadow rays 1.05-1.07x faster on
/// the SF 4 mesh, docs/results.md); `build` keeps the source tree's order.
enum class ChildOrder { area, build };

/// The same tree with every leaf's first prim_ids slot a multiple of `k` (k <= 1: unchanged):
/// leaves keep their order and the slots between them hold padding_slot. With k the SIMD group of
/// slot-ordered leaf data (4), a leaf's data starts a group and a leaf of up to 8 primitives is
/// one 8-lane chunk of the leaf kernels instead of up to two.
Bvh align_leaf_slots(Bvh bvh, std::uint32_t k);

}  // namespace rtlab
