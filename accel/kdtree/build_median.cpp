// Spatial-median kd-tree: every node is split at the middle of its longest axis (the classic
// baseline; Kaplan 1985, cited by Havran 2000). It stops where the SAH builder would: at
// min_leaf_size, at max_depth, or when the split's SAH cost is not below the leaf's.
// Straddling primitives go to both sides with clipped boxes (BuildInput::clip when given and
// Config::perfect_splits is on).
// Cost: O(N log N) for balanced scenes (each level touches each reference once). Subtrees build
// in parallel with Config::threads; the tree is the same for any thread count.

#include "accel/kdtree/build_common.h"
#include "accel/kdtree/kdtree.h"
#include "base/thread_arena.h"

#include <cstdint>
#include <stdexcept>
#include <tbb/parallel_invoke.h>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// A primitive reference: id and its box clipped to the current node.
struct Ref {
    std::uint32_t id;
    Bounds3f box;
};

class MedianBuilder : kd_detail::BuilderSettings {
public:
    using BuilderSettings::BuilderSettings;

    /// Builds the subtree of the node `box` holding `refs` into `out` (nodes and lists only).
    void recurse(std::vector<Ref> refs, const Bounds3f& box, std::uint32_t depth, KdTree& out) {
        const std::size_t n = refs.size();
        const auto axis = static_cast<std::uint32_t>(box.largest_axis());
        const float mid = box.center()[axis];
        std::size_t nl = 0, nr = 0;
        for (const Ref& r : refs) {
            nl += r.box.lo[axis] < mid || r.box.hi[axis] <= mid ? 1 : 0;
            nr += r.box.hi[axis] > mid ? 1 : 0;
        }
        const bool can_split = n > min_leaf_ && depth < max_depth_ && mid > box.lo[axis] &&
                               mid < box.hi[axis] &&
                               cost_.split_cost(box, axis, mid, nl, nr) < cost_.leaf_cost(n);
        if (!can_split) {
            std::vector<std::uint32_t> ids;
            ids.reserve(n);
            for (const Ref& r : refs) {
                ids.push_back(r.id);
            }
            kd_detail::emit_leaf(out, ids);
            return;
        }
        const Bounds3f left_box = kd_detail::half_box(box, axis, mid, 0);
        const Bounds3f right_box = kd_detail::half_box(box, axis, mid, 1);
        std::vector<Ref> left, right;
        for (const Ref& r : refs) {
            if (r.box.hi[axis] <= mid) {
                left.push_back(r);  // includes primitives lying in the plane
            } else if (r.box.lo[axis] >= mid) {
                right.push_back(r);
            } else {
                Bounds3f lb = clip(r.id, left_box), rb = clip(r.id, right_box);
                if (!is_usable_box(lb) && !is_usable_box(rb)) {
                    lb = intersection(r.box, left_box);
                    rb = intersection(r.box, right_box);
                }
                if (is_usable_box(lb)) {
                    left.push_back({r.id, lb});
                }
                if (is_usable_box(rb)) {
                    right.push_back({r.id, rb});
                }
            }
        }
        refs.clear();
        refs.shrink_to_fit();
        const std::uint32_t index = kd_detail::emit_inner(out, axis, mid);
        if (parallel_ && n >= parallel_min) {
            // Both children as tasks into their own arrays, appended in pre-order: the same
            // tree as the serial recursion.
            KdTree lt, rt;
            tbb::parallel_invoke([&] { recurse(std::move(left), left_box, depth + 1, lt); },
                                 [&] { recurse(std::move(right), right_box, depth + 1, rt); });
            append(out, lt);
            kd_detail::link_above(out, index);
            append(out, rt);
            return;
        }
        recurse(std::move(left), left_box, depth + 1, out);
        kd_detail::link_above(out, index);
        recurse(std::move(right), right_box, depth + 1, out);
    }

    /// Nodes with at least this many references build their children as parallel tasks.
    static constexpr std::size_t parallel_min = 4096;

private:
    /// Appends a subtree built on its own (indices from 0) to t's nodes and lists.
    static void append(KdTree& t, const KdTree& sub) {
        const std::size_t node_shift = t.nodes.size(), list_shift = t.prim_ids.size();
        if (node_shift + sub.nodes.size() > KdNode::max_index ||
            list_shift + sub.prim_ids.size() > 0xFFFFFFFFu) {
            throw std::length_error("kd-tree: too many nodes or primitive references");
        }
        for (const KdNode& n : sub.nodes) {
            t.nodes.push_back(
                n.is_leaf()
                    ? KdNode::leaf(n.prim_offset() + static_cast<std::uint32_t>(list_shift),
                                   n.prim_count())
                    : KdNode::inner(n.axis(), n.split(),
                                    n.above_child() + static_cast<std::uint32_t>(node_shift)));
        }
        t.prim_ids.insert(t.prim_ids.end(), sub.prim_ids.begin(), sub.prim_ids.end());
    }

    /// The part of primitive id inside box (empty when none).
    Bounds3f clip(std::uint32_t id, const Bounds3f& box) const {
        if (perfect_) {
            return intersection(in_.clip(id, box), box);
        }
        return intersection(in_.bounds[id], box);
    }
};

}  // namespace

KdTree build_kdtree_median(const BuildInput& in, const KdTree::Config& cfg) {
    return with_threads(cfg.threads, [&] {
        KdTree tree = kd_detail::start_tree(in, cfg);
        std::vector<Ref> refs;
        refs.reserve(in.bounds.size());
        for (std::uint32_t id = 0; id < in.bounds.size(); ++id) {
            if (tree.prim_present[id]) {
                refs.push_back({id, in.bounds[id]});
            }
        }
        MedianBuilder builder(in, cfg, tree.max_depth, cfg.threads != 1);
        builder.recurse(std::move(refs), tree.scene_bounds, 0, tree);
        return tree;
    });
}

}  // namespace rtlab
