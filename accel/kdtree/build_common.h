#pragma once
// Shared by the kd-tree builders: the SAH cost model (Wald & Havran 2006, section 4.1, with the
// empty-space bonus), the resolved depth limit, and node emission in pre-order through the shared
// TaskTree (accel/task_tree.h).

#include "accel/kdtree/kdtree.h"
#include "accel/task_tree.h"
#include "base/large_pages.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>

namespace rtlab::kd_detail {

/// Depth limit: cfg.max_depth, or 8 + 1.3 log2 N (pbrt) when 0; never above KdTree::depth_limit.
inline std::uint32_t resolve_max_depth(const KdTree::Config& cfg, std::size_t n) {
    std::uint32_t d = cfg.max_depth;
    if (d == 0) {
        const double log_n = n > 1 ? std::log2(static_cast<double>(n)) : 0.0;
        d = static_cast<std::uint32_t>(std::lround(8.0 + 1.3 * log_n));
    }
    return std::min(d, KdTree::depth_limit);
}

/// The box split at `pos` along `axis`: which = 0 gives the part below, 1 the part above.
inline Bounds3f half_box(const Bounds3f& box, std::uint32_t axis, float pos, int which) {
    Bounds3f b = box;
    if (which == 0) {
        b.hi[axis] = pos;
    } else {
        b.lo[axis] = pos;
    }
    return b;
}

/// SAH cost model shared by both builders.
struct CostModel {
    float kt = 1.0f;     ///< traversal cost
    float ki = 1.5f;     ///< intersection cost
    float bonus = 0.8f;  ///< empty-space bonus

    /// Cost of splitting `box` at `pos` along `axis` with nl / nr primitives on each side:
    /// (1 - bonus if a side is empty) * (K_T + K_I (P_L n_L + P_R n_R)), P = SA(side)/SA(box).
    /// Returns +inf for a box of zero area (never split).
    double split_cost(
        const Bounds3f& box, std::uint32_t axis, float pos, std::size_t nl, std::size_t nr) const {
        const double sa = static_cast<double>(box.surface_area());
        if (!(sa > 0.0)) {
            return HUGE_VAL;
        }
        const double pl = static_cast<double>(half_box(box, axis, pos, 0).surface_area()) / sa;
        const double pr = static_cast<double>(half_box(box, axis, pos, 1).surface_area()) / sa;
        const double lambda = (nl == 0 || nr == 0) ? 1.0 - static_cast<double>(bonus) : 1.0;
        return lambda *
               (static_cast<double>(kt) + static_cast<double>(ki) * (pl * static_cast<double>(nl) +
                                                                     pr * static_cast<double>(nr)));
    }
    /// Cost of a leaf with n primitives: K_I n.
    double leaf_cost(std::size_t n) const {
        return static_cast<double>(ki) * static_cast<double>(n);
    }
};

/// What both builders keep of their input and Config: the input, the cost model, the leaf size
/// and depth limits and whether straddling primitives are clipped (perfect splits, given a clip).
class BuilderSettings {
public:
    BuilderSettings(const BuildInput& in, const KdTree::Config& cfg, std::uint32_t max_depth)
        : in_(in)
        , cost_{cfg.traversal_cost, cfg.intersection_cost, cfg.empty_bonus}
        , min_leaf_(cfg.min_leaf_size)
        , max_depth_(max_depth)
        , perfect_(cfg.perfect_splits && static_cast<bool>(in.clip)) {}

protected:
    const BuildInput& in_;
    CostModel cost_;
    std::size_t min_leaf_;
    std::uint32_t max_depth_;
    bool perfect_;
};

/// A kd-tree with the bookkeeping fields set from the input, and no nodes yet; primitives whose
/// box fails is_usable_box are marked absent.
inline KdTree start_tree(const BuildInput& in, const KdTree::Config& cfg) {
    if (in.bounds.size() > KdNode::max_index) {
        throw std::length_error("kd-tree: too many primitives for 30-bit counts");
    }
    KdTree t;
    t.prim_present.resize(in.bounds.size());
    std::size_t present = 0;
    for (std::size_t i = 0; i < in.bounds.size(); ++i) {
        if (is_usable_box(in.bounds[i])) {
            t.prim_present[i] = true;
            t.scene_bounds.extend(in.bounds[i]);
            ++present;
        }
    }
    t.max_depth = resolve_max_depth(cfg, present);
    t.traversal_cost = cfg.traversal_cost;
    t.intersection_cost = cfg.intersection_cost;
    t.traversal = cfg.traversal;
    return t;
}

/// Subtrees of at least this many primitives are tasks of the kd-tree builders' TaskTree.
inline constexpr std::uint32_t task_min = 4096;

/// The task tree of the kd-tree builders: nodes in pre-order, leaf lists per chunk.
using KdTaskTree = TaskTree<LargeVector<KdNode>, LargeVector<std::uint32_t>>;

/// Writes the leaf holding `ids` (sorted for a canonical order) to out.nodes[slot].
inline void put_leaf(KdTaskTree::Chunk& out, std::uint32_t slot, std::span<std::uint32_t> ids) {
    if (ids.size() > KdNode::max_index) {
        throw std::length_error("kd-tree: too many primitives in one leaf");
    }
    std::sort(ids.begin(), ids.end());
    out.nodes[slot] = KdNode::leaf(static_cast<std::uint32_t>(out.ids.size()),
                                   static_cast<std::uint32_t>(ids.size()));
    out.ids.insert(out.ids.end(), ids.begin(), ids.end());
}

/// Builds both children of the inner node at out.nodes[slot] (split `pos` on `axis`) through
/// tree.fork, each root added where its nodes start (pre-order), and links the node above.
template <class L, class R>
void put_inner(KdTaskTree& tree,
               KdTaskTree::Chunk& out,
               std::uint32_t slot,
               std::uint32_t axis,
               float pos,
               TaskBranch<L> below,
               TaskBranch<R> above) {
    const std::uint32_t above_slot = tree.fork(out, below, above).second;
    out.nodes[slot] = KdNode::inner(axis, pos, above_slot);
}

/// Lays the task tree's chunks out as t's nodes and leaf lists (TaskTree::splice).
inline void splice(KdTaskTree& tree, KdTree& t) {
    tree.splice(t.nodes, &t.prim_ids, [](KdNode n, const auto& node_of, const auto& id_of) {
        return n.is_leaf() ? KdNode::leaf(
                                 static_cast<std::uint32_t>(id_of(n.prim_offset(), n.prim_count())),
                                 n.prim_count())
                           : KdNode::inner(n.axis(), n.split(),
                                           static_cast<std::uint32_t>(node_of(n.above_child())));
    });
    if (t.nodes.size() - 1 > KdNode::max_index || t.prim_ids.size() > 0xFFFFFFFFu) {
        throw std::length_error("kd-tree: too many nodes or primitive references");
    }
}

}  // namespace rtlab::kd_detail
