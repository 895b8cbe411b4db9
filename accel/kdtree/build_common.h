#pragma once
// Shared by the kd-tree builders: the SAH cost model (Wald & Havran 2006, section 4.1, with the
// empty-space bonus), the resolved depth limit, and node emission in pre-order.

#include "accel/kdtree/kdtree.h"

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
/// and depth limits, whether straddling primitives are clipped (perfect splits, given a clip) and
/// whether children are built as parallel tasks.
class BuilderSettings {
public:
    BuilderSettings(const BuildInput& in,
                    const KdTree::Config& cfg,
                    std::uint32_t max_depth,
                    bool parallel)
        : in_(in)
        , cost_{cfg.traversal_cost, cfg.intersection_cost, cfg.empty_bonus}
        , min_leaf_(cfg.min_leaf_size)
        , max_depth_(max_depth)
        , perfect_(cfg.perfect_splits && static_cast<bool>(in.clip))
        , parallel_(parallel) {}

protected:
    const BuildInput& in_;
    CostModel cost_;
    std::size_t min_leaf_;
    std::uint32_t max_depth_;
    bool perfect_;
    bool parallel_;
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
    t.soa_leaves = cfg.soa_leaves;
    return t;
}

/// Appends a leaf holding `ids` (sorted for a canonical order); returns its index.
inline std::uint32_t emit_leaf(KdTree& t, std::span<std::uint32_t> ids) {
    std::sort(ids.begin(), ids.end());
    const auto index = static_cast<std::uint32_t>(t.nodes.size());
    if (t.prim_ids.size() + ids.size() > 0xFFFFFFFFu || ids.size() > KdNode::max_index) {
        throw std::length_error("kd-tree: too many primitive references");
    }
    t.nodes.push_back(KdNode::leaf(static_cast<std::uint32_t>(t.prim_ids.size()),
                                   static_cast<std::uint32_t>(ids.size())));
    t.prim_ids.insert(t.prim_ids.end(), ids.begin(), ids.end());
    return index;
}

/// Appends an inner node whose above child is not known yet; returns its index.
inline std::uint32_t emit_inner(KdTree& t, std::uint32_t axis, float split) {
    const auto index = static_cast<std::uint32_t>(t.nodes.size());
    t.nodes.push_back(KdNode::inner(axis, split, 0));
    return index;
}

/// Sets the above child of inner node `index` to the next node to be emitted.
inline void link_above(KdTree& t, std::uint32_t index) {
    const auto above = static_cast<std::uint32_t>(t.nodes.size());
    if (above > KdNode::max_index) {
        throw std::length_error("kd-tree: too many nodes for 30-bit indices");
    }
    const KdNode n = t.nodes[index];
    t.nodes[index] = KdNode::inner(n.axis(), n.split(), above);
}

}  // namespace rtlab::kd_detail
