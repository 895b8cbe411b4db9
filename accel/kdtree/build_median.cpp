// Spatial-median kd-tree: every node is split at the middle of its longest axis (the classic
// baseline; Kaplan 1985, cited by Havran 2000). It stops where the SAH builder would: at
// min_leaf_size, at max_depth, or when the split's SAH cost is not below the leaf's.
// Straddling primitives go to both sides with clipped boxes (BuildInput::clip when given and
// Config::perfect_splits is on).
// Cost: O(N log N) for balanced scenes (each level touches each reference once). Subtrees build
// in parallel with Config::threads (the shared TaskTree); the tree is the same for any thread
// count.

#include "accel/kdtree/build_common.h"
#include "accel/kdtree/kdtree.h"
#include "base/thread_arena.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// A primitive reference: id and its box clipped to the current node.
struct Ref {
    std::uint32_t id;
    Bounds3f box;
};

using Tree = kd_detail::KdTaskTree;
using Chunk = Tree::Chunk;

class MedianBuilder : kd_detail::BuilderSettings {
public:
    using BuilderSettings::BuilderSettings;

    /// Builds the subtree of the node `box` holding `refs` into out.nodes[slot] and below.
    void recurse(kd_detail::KdTaskTree& tree,
                 Chunk& out,
                 std::uint32_t slot,
                 std::vector<Ref> refs,
                 const Bounds3f& box,
                 std::uint32_t depth) {
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
            kd_detail::put_leaf(out, slot, ids);
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
        const std::size_t left_n = left.size(), right_n = right.size();
        kd_detail::put_inner(
            tree, out, slot, axis, mid,
            TaskBranch{Tree::append, left_n,
                       [&](Chunk& c, std::uint32_t at) {
                           recurse(tree, c, at, std::move(left), left_box, depth + 1);
                       }},
            TaskBranch{Tree::append, right_n, [&](Chunk& c, std::uint32_t at) {
                           recurse(tree, c, at, std::move(right), right_box, depth + 1);
                       }});
    }

private:
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
        MedianBuilder builder(in, cfg, tree.max_depth);
        Tree tasks({kd_detail::task_min, cfg.threads != 1, 0}, refs.size());
        builder.recurse(tasks, tasks.root(), 0, std::move(refs), tree.scene_bounds, 0);
        kd_detail::splice(tasks, tree);
        return tree;
    });
}

}  // namespace rtlab
