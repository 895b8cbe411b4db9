#pragma once
// kd-tree: 8-byte nodes, built by the O(N log N) SAH sweep of Wald & Havran 2006 (build_sah.cpp)
// or by spatial medians (build_median.cpp), both listed in accel/registry.cpp; traversed front to
// back either by Havran's TA^B_rec (thesis 2000: entry and exit points on the stack,
// accel/kdtree/havran.h) or by pbrt's stack of (node, t_enter, t_exit) (spec `traversal=`). A
// primitive may be referenced by several leaves, so a hit beyond the current leaf does not end the
// traversal. Leaves are ranges of prim_ids, so tracers may store triangles in that order and test
// a whole leaf with a SIMD kernel (LeafRangeAccel, spec `leaves=`). Cost per ray: O(depth)
// inner-node steps per leaf visited plus the leaf primitives.

#include "accel/accel.h"
#include "accel/kdtree/havran.h"
#include "accel/kdtree/node.h"
#include "accel/window_leaf.h"
#include "base/large_pages.h"
#include "intersect/box/slabs.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rtlab {

/// How KdTree walks its nodes: Havran's TA^B_rec (entry and exit points, accel/kdtree/havran.h)
/// or pbrt's t-value stack; both visit the same leaves in the same order up to rounding.
enum class KdTraversal : std::uint8_t { havran, tvalue };

/// A kd-tree over primitive boxes; nodes[0] is the root, prim_ids holds the leaves' lists.
struct KdTree : LeafWalkQueries<KdTree> {
    /// Build parameters; the cost constants are those of the SAH cost model.
    struct Config {
        float traversal_cost = 1.0f;     ///< K_T: cost of one inner-node step
        float intersection_cost = 1.5f;  ///< K_I: cost of one ray-primitive test
        float empty_bonus = 0.8f;        ///< split cost is scaled by (1 - bonus) if a side is empty
        std::uint32_t max_depth = 0;     ///< deepest leaf; 0 = 8 + 1.3 log2 N (pbrt); capped at 64
        std::uint32_t min_leaf_size = 1;  ///< nodes with at most this many primitives are leaves
        /// Perfect splits (Havran 2000; Wald & Havran 2006): a straddling primitive's part on
        /// each side is BuildInput::clip of it (the clipped triangle's box) when a clip is given;
        /// off, or without a clip, it is its box cut at the plane.
        bool perfect_splits = true;
        std::uint32_t threads = 0;  ///< TBB threads of the SAH build (0: all allowed); same tree
        KdTraversal traversal = KdTraversal::havran;  ///< copied to the tree (not a build choice)
    };

    /// Deepest possible leaf whatever the configuration; sizes the traversal stack.
    static constexpr std::uint32_t depth_limit = 64;

    // Nodes and lists in huge pages once 2 MiB or more (base/large_pages.h), as bvh:pair's.
    LargeVector<KdNode> nodes;            ///< pre-order; an inner node's below child follows it
    LargeVector<std::uint32_t> prim_ids;  ///< leaf primitive lists (caller's primitive ids)
    Bounds3f scene_bounds;                ///< union of the non-empty primitive boxes
    std::vector<bool> prim_present;       ///< per primitive id: its box passes is_usable_box
    std::uint32_t max_depth = 0;          ///< the depth limit the build used
    float traversal_cost = 1.0f;          ///< K_T the build used (for info().sah_cost)
    float intersection_cost = 1.5f;       ///< K_I the build used (for info().sah_cost)
    KdTraversal traversal = KdTraversal::havran;  ///< the walk intersect/occluded use

    /// Closest hit offering whole leaves: leaf_fn(first, count, ray) tests the primitives of
    /// prim_ids slots [first, first + count) in slot order, shrinks ray.tmax on a hit and returns
    /// true; same leaves, order and stop rule as intersect. For leaf data stored in slot order
    /// (a primitive in several leaves is stored once per reference).
    template <bool IsRobust = false, LeafRangeFn<Rayf> F, StatsSink S = NoStats>
    bool intersect_leaves(Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        bool hit = false;
        auto leaf = [&](std::uint32_t first, std::uint32_t count) {
            if (count != 0) {
                stats.count_prims(count);
                hit = leaf_fn(first, count, ray) || hit;
            }
            return false;
        };
        walk_leaves<IsRobust>(ray, stats, leaf);
        return hit;
    }

    /// Any hit offering whole leaves: the first leaf_fn(first, count, ray) returning true ends it.
    template <bool IsRobust = false, LeafRangeFn<const Rayf> F, StatsSink S = NoStats>
    bool occluded_leaves(const Rayf& ray, F&& leaf_fn, S&& stats = {}) const {
        Rayf r = ray;
        auto leaf = [&](std::uint32_t first, std::uint32_t count) {
            stats.count_prims(count);
            return count != 0 && static_cast<bool>(leaf_fn(first, count, ray));
        };
        return walk_leaves<IsRobust>(r, stats, leaf);
    }

    /// Union of the non-empty primitive boxes.
    Bounds3f bounds() const { return scene_bounds; }

    /// Node, leaf and byte counts; sah_cost is the SAH cost-model value of the tree,
    /// sum over inner nodes K_T * SA(node)/SA(root) + sum over leaves K_I * n * SA(leaf)/SA(root).
    AccelInfo info() const;

    /// Checks: node indices and leaf lists in range, each split inside its node's box, depth at
    /// most max_depth, every primitive with a non-empty box referenced at least once.
    std::string validate() const;

    friend bool operator==(const KdTree&, const KdTree&) = default;

private:
    /// Checks and clips the ray, then walks the leaves its window meets front to back with the
    /// chosen traversal, calling leaf(first, count) for each (true stops the walk). Rays with a
    /// zero or denormal direction component (the only ones that can lie in a split plane) take
    /// the t-value walk, which visits both children of such a plane. Returns whether leaf stopped.
    template <bool IsRobust, class S, class Leaf>
    bool walk_leaves(Rayf& ray, S& stats, Leaf& leaf) const {
        if (!is_valid(ray) || nodes.empty()) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        float t_enter = ray.tmin, t_exit = ray.tmax;
        if (!clip_slabs<IsRobust>(scene_bounds.lo, scene_bounds.hi, sr, t_enter, t_exit)) {
            return false;
        }
        if (traversal == KdTraversal::havran && std::isfinite(sr.inv_dir.x) &&
            std::isfinite(sr.inv_dir.y) && std::isfinite(sr.inv_dir.z)) {
            return kd_detail::havran_walk<IsRobust, depth_limit>(nodes.data(), ray, sr, t_enter,
                                                                 t_exit, stats, leaf);
        }
        return tvalue_walk<IsRobust>(ray, sr, t_enter, t_exit, stats, leaf);
    }

    friend LeafWalkQueries<KdTree>;

    /// walk_leaves offering each leaf's primitive ids to visit(id) one by one (true stops): the
    /// walk of intersect and occluded (LeafWalkQueries). Invalid rays (NaN, zero direction) are
    /// rejected before any node is touched.
    template <bool IsRobust, class S, class Visit>
    bool walk_ids(Rayf& ray, S& stats, Visit& visit) const {
        auto leaf = [&](std::uint32_t first, std::uint32_t count) {
            for (std::uint32_t i = first; i < first + count; ++i) {
                if (visit(prim_ids[i])) {
                    return true;
                }
            }
            return false;
        };
        return walk_leaves<IsRobust>(ray, stats, leaf);
    }

    /// The t-value walk (pbrt): a stack of (node, t_enter, t_exit). After a leaf, only subtrees
    /// whose window starts at or before ray.tmax are visited, so the walk ends once ray.tmax <=
    /// that leaf's t_exit.
    template <bool IsRobust, class S, class Leaf>
    bool tvalue_walk(Rayf& ray,
                     const SlabRay<float>& sr,
                     float t_enter,
                     float t_exit,
                     S& stats,
                     Leaf& leaf) const {
        struct Entry {
            std::uint32_t node;
            float t_enter, t_exit;
        };
        Entry stack[depth_limit + 1];
        std::uint32_t top = 0;
        std::uint32_t index = 0;
        for (;;) {
            const KdNode& n = nodes[index];
            stats.count_node();
            if (!n.is_leaf()) {
                const std::uint32_t a = n.axis();
                const float split = n.split();
                // "First" is the child the ray enters first: below for a positive direction.
                const std::uint32_t below = index + 1, above = n.above_child();
                const std::uint32_t first = sr.neg[a] ? above : below;
                const std::uint32_t second = sr.neg[a] ? below : above;
                const float t_split = (split - sr.org[a]) * sr.inv_dir[a];
                if (t_split != t_split) {
                    // 0 * inf: the ray lies in the split plane, which both closed children share.
                    stack[top++] = {second, t_enter, t_exit};
                    index = first;
                    continue;
                }
                // Robust: t_split carries the rounding of a subtraction, a multiplication and
                // the reciprocal, so widen it by gamma(3) on each side (as the slab test does).
                float lo_split = t_split, hi_split = t_split;
                if constexpr (IsRobust) {
                    const float pad = std::abs(t_split) * (2.0f * gamma_bound<float>(3));
                    if (std::isfinite(pad)) {
                        lo_split -= pad;
                        hi_split += pad;
                    }
                }
                const bool visit_first = t_enter <= hi_split;
                const bool visit_second = lo_split <= t_exit;
                if (visit_first && visit_second) {
                    stack[top++] = {second, lo_split > t_enter ? lo_split : t_enter, t_exit};
                    index = first;
                    t_exit = hi_split < t_exit ? hi_split : t_exit;
                    continue;
                }
                if (visit_first || visit_second) {
                    index = visit_first ? first : second;
                    continue;
                }
                // Neither (only for a NaN-free empty window, which clip_slabs rules out).
            } else if (leaf(n.prim_offset(), n.prim_count())) {
                return true;
            }
            // Pop the next subtree whose window starts at or before ray.tmax. Once ray.tmax <=
            // this leaf's t_exit, the front-to-back order leaves only subtrees starting at or
            // after it, so this ends the walk; the exception is a ray lying in a split plane,
            // whose two children share one window and must both be searched.
            for (;;) {
                if (top == 0) {
                    return false;
                }
                const Entry e = stack[--top];
                if (e.t_enter <= ray.tmax) {
                    index = e.node;
                    t_enter = e.t_enter;
                    t_exit = e.t_exit < ray.tmax ? e.t_exit : ray.tmax;
                    break;
                }
            }
        }
    }
};

static_assert(Accel<KdTree>);
static_assert(LeafRangeAccel<KdTree>);

}  // namespace rtlab
