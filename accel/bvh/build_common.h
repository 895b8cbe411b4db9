#pragma once
// Shared machinery of the BVH builders (internal to accel/bvh): which boxes are usable, the
// top-down recursion that emits Wald nodes in depth-first pair order (in parallel when asked), the
// object-median split and the depth guard that keeps every leaf at depth <= 64.

#include "accel/bvh/bvh.h"
#include "base/thread_arena.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <tbb/parallel_invoke.h>
#include <vector>

namespace rtlab::bvh_detail {

/// Empty when prim_ids references every usable primitive exactly once (ids < prim_count, none
/// twice, prim_count - unreferenced_count of them); else the first violation. Shared by the
/// validate() of every BVH layout.
std::string check_prim_ids(std::span<const std::uint32_t> prim_ids,
                           std::uint32_t prim_count,
                           std::uint32_t unreferenced_count);

/// ceil(log2(n)) for n >= 1 (0 for n = 1).
std::uint32_t ceil_log2(std::uint64_t n);

/// The configuration with every field clamped to its documented range.
Bvh::Config clamped(const Bvh::Config& cfg);

/// True when the SAH makes a range of n primitives a leaf whatever its splits: it fits one and
/// Ci * n <= Ct, so its leaf cost Ci * n * A is at most Ct * A, which no split's
/// Ct * A + Ci * (A_L n_L + A_R n_R) undercuts (for a finite area A; rounding is monotone, so in
/// floats too). The SAH builders make such ranges leaves without binning or sweeping them, as
/// Embree's builders make every range of up to minLeafSize primitives a leaf.
inline bool sah_leaf_anyway(const Bvh::Config& cfg, std::uint32_t n) {
    return n <= cfg.max_leaf_size &&
           cfg.intersection_cost * static_cast<float>(n) <= cfg.traversal_cost;
}

/// A split of the id range [b, e): [b, mid) goes left, [mid, e) right (b < mid < e).
struct Split {
    std::uint32_t mid;   ///< first slot of the right child
    std::uint32_t axis;  ///< split axis stored in the node to order traversal
};

/// State of one top-down build: input boxes, centres, the working order of usable primitive ids
/// (each node owns a contiguous range of it) and the output tree.
class TopDown {
public:
    /// Collects the usable primitives of `in` in id order; cfg must already be clamped.
    TopDown(const BuildInput& in, const Bvh::Config& cfg);

    std::span<const Bounds3f> boxes;  ///< input boxes by primitive id
    std::vector<Vec3f> centers;       ///< box centres by primitive id
    std::vector<std::uint32_t> ids;   ///< usable primitive ids; node ranges index into it
    Bvh::Config config;               ///< clamped configuration

    /// Union of the boxes of ids[b, e).
    Bounds3f range_bounds(std::uint32_t b, std::uint32_t e) const;
    /// Union of the centres of ids[b, e).
    Bounds3f centroid_bounds(std::uint32_t b, std::uint32_t e) const;
    /// Object median of ids[b, e) on the largest centroid axis (ties by id); reorders the range.
    Split median_split(std::uint32_t b, std::uint32_t e);
    /// True when a split of n primitives at `depth` must be balanced (children <= ceil(n/2)) so
    /// that every leaf below stays at depth <= 64: invariant depth + ceil_log2(n) <= 64.
    static bool must_balance(std::uint32_t depth, std::uint32_t n);

    /// Runs the recursion, children of large ranges as parallel TBB tasks when `parallel`.
    /// split(*this, b, e, box, balance) returns a Split or nullopt for a leaf; when balance is true
    /// it must return a balanced split, and it must split whenever e - b > max_leaf_size. It may
    /// run concurrently on disjoint ranges, touching only ids[b, e) and scratch of its own range or
    /// thread. Returns the finished tree, the same for any thread count.
    template <class SplitFn>
    Bvh run(SplitFn&& split, bool parallel = false) {
        Bvh bvh;
        bvh.prim_count = static_cast<std::uint32_t>(boxes.size());
        bvh.unreferenced_count = bvh.prim_count - static_cast<std::uint32_t>(ids.size());
        bvh.config = config;
        if (!ids.empty()) {
            bvh.nodes.reserve(2 * ids.size() - 1);
            bvh.nodes.emplace_back();
            const auto n = static_cast<std::uint32_t>(ids.size());
            build_node(bvh.nodes, split, 0, 0, n, 0, range_bounds(0, n), parallel);
        }
        bvh.prim_ids = ids;
        return bvh;
    }

    /// Ranges at least this large build their two children as parallel tasks.
    static constexpr std::uint32_t parallel_min = 4096;

private:
    // Fills nodes[node] with the subtree of ids[b, e), appending its descendants to `nodes` in
    // depth-first pair order (both children, then the left subtree, then the right). In
    // parallel, large children build into their own arrays, spliced in that same order.
    template <class SplitFn>
    void build_node(BvhNodes& nodes,
                    SplitFn& split,
                    std::uint32_t node,
                    std::uint32_t b,
                    std::uint32_t e,
                    std::uint32_t depth,
                    const Bounds3f& box,
                    bool parallel) {
        const std::uint32_t n = e - b;
        std::optional<Split> s;
        if (n > 1) {
            s = split(*this, b, e, box, must_balance(depth, n));
            if (!s && n > config.max_leaf_size) {
                s = median_split(b, e);
            }
        }
        if (!s) {
            nodes[node] = BvhNode::make_leaf(box, b, n);
            return;
        }
        const auto left = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        nodes.emplace_back();
        nodes[node] = BvhNode::make_inner(box, left, s->axis);
        const Bounds3f left_box = range_bounds(b, s->mid), right_box = range_bounds(s->mid, e);
        if (parallel && n >= parallel_min) {
            BvhNodes l(1), r(1);
            l.reserve(2 * (s->mid - b) - 1);  // a subtree of k primitives has <= 2k - 1 nodes
            r.reserve(2 * (e - s->mid) - 1);
            tbb::parallel_invoke(
                [&] { build_node(l, split, 0, b, s->mid, depth + 1, left_box, true); },
                [&] { build_node(r, split, 0, s->mid, e, depth + 1, right_box, true); });
            splice(nodes, left, l);
            splice(nodes, left + 1, r);
            return;
        }
        build_node(nodes, split, left, b, s->mid, depth + 1, left_box, parallel);
        build_node(nodes, split, left + 1, s->mid, e, depth + 1, right_box, parallel);
    }

    /// Puts sub[0] at nodes[slot] and appends sub[1..]: index k >= 1 of sub moves to
    /// nodes.size() + k - 1, so child links are shifted by that much.
    static void splice(BvhNodes& nodes, std::uint32_t slot, const BvhNodes& sub);
};

}  // namespace rtlab::bvh_detail
