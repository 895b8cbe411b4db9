// SAH kd-tree in O(N log N): Wald & Havran 2006, "On building fast kd-trees for ray tracing, and
// on doing that in O(N log N)". Per-axis event lists (end < planar < start at equal positions,
// packed 64-bit events, accel/kdtree/events.h) are radix-sorted once; each node sweeps them to
// find the cheapest plane (planar primitives go to the cheaper side), classifies primitives left
// / right / both, and splits the lists in linear time. Straddling primitives: without perfect
// splits their box is cut at the plane, which moves one event on the split axis only (no sort);
// with perfect splits (Config::perfect_splits and a BuildInput::clip) each part is the clipped
// triangle's box on the side, whose events are sorted and merged back in. Planes on the node's
// boundary are not candidates (they would repeat the node).
// Parallel: subtrees of large nodes are tasks of the shared TaskTree (accel/task_tree.h), so the
// tree is the same for any thread count.

#include "accel/kdtree/build_common.h"
#include "accel/kdtree/events.h"
#include "accel/kdtree/kdtree.h"
#include "base/thread_arena.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>
#include <vector>

namespace rtlab {

namespace {

using kd_detail::Event;
using kd_detail::event_end;
using kd_detail::event_planar;
using kd_detail::event_pos;
using kd_detail::event_pos_bits;
using kd_detail::event_prim;
using kd_detail::event_start;
using kd_detail::event_type;
using kd_detail::EventLists;
using kd_detail::make_event;

/// Appends the events of `box` (non-empty) for primitive `id` on every axis.
void add_events(EventLists& ev, std::uint32_t id, const Bounds3f& box) {
    for (std::size_t k = 0; k < 3; ++k) {
        if (box.lo[k] == box.hi[k]) {
            ev[k].push_back(make_event(box.lo[k], event_planar, id));
        } else {
            ev[k].push_back(make_event(box.lo[k], event_start, id));
            ev[k].push_back(make_event(box.hi[k], event_end, id));
        }
    }
}

/// Merges the sorted `extra` into the sorted `list`.
void merge_sorted(std::vector<Event>& list, const std::vector<Event>& extra) {
    if (extra.empty()) {
        return;
    }
    std::vector<Event> merged(list.size() + extra.size());
    std::merge(list.begin(), list.end(), extra.begin(), extra.end(), merged.begin());
    list = std::move(merged);
}

/// Where a primitive goes at the current split.
enum Side : std::uint8_t { side_both = 0, side_left = 1, side_right = 2 };

/// The best plane of one node.
struct Plane {
    double cost = HUGE_VAL;
    std::uint32_t axis = 0;
    float pos = 0;
    bool planar_left = true;  ///< primitives lying in the plane go to the left (below) child
};

using Tree = kd_detail::KdTaskTree;
using Chunk = Tree::Chunk;

class SahBuilder : kd_detail::BuilderSettings {
public:
    SahBuilder(const BuildInput& in, const KdTree::Config& cfg, std::uint32_t max_depth)
        : BuilderSettings(in, cfg, max_depth) {}

    /// Builds the subtree of the node `box` whose primitives' events are `ev` into
    /// out.nodes[slot] and below.
    void build(Tree& tree,
               Chunk& out,
               std::uint32_t slot,
               EventLists ev,
               const Bounds3f& box,
               std::uint32_t depth) {
        std::vector<std::uint32_t> ids;
        for (const Event e : ev[0]) {
            if (event_type(e) != event_end) {
                ids.push_back(event_prim(e));
            }
        }
        const std::size_t n = ids.size();
        const Plane best = n <= min_leaf_ || depth >= max_depth_ ? Plane{} : find_plane(ev, box, n);
        if (!(best.cost < cost_.leaf_cost(n))) {
            kd_detail::put_leaf(out, slot, ids);
            return;
        }
        // One side byte per primitive id for this thread: classify and split_lists run without
        // a task in between.
        std::unique_ptr<Side[]>& side = sides_.local();
        if (side == nullptr) {
            side = std::make_unique_for_overwrite<Side[]>(in_.bounds.size());
        }
        classify(ev[best.axis], ids, best, side.get());
        EventLists left, right;
        split_lists(ev, best, ids, box, side.get(), left, right);
        const Bounds3f left_box = kd_detail::half_box(box, best.axis, best.pos, 0);
        const Bounds3f right_box = kd_detail::half_box(box, best.axis, best.pos, 1);
        // Both children are tasks when this node has task_min primitives or more (counting
        // theirs would take another pass over the ids).
        kd_detail::put_inner(
            tree, out, slot, best.axis, best.pos,
            TaskBranch{Tree::append, n,
                       [&](Chunk& c, std::uint32_t at) {
                           build(tree, c, at, std::move(left), left_box, depth + 1);
                       }},
            TaskBranch{Tree::append, n, [&](Chunk& c, std::uint32_t at) {
                           build(tree, c, at, std::move(right), right_box, depth + 1);
                       }});
    }

private:
    /// The sweep over the three sorted event lists (Wald & Havran, algorithm 4). Surface areas
    /// of the two sides are linear in the plane position, so each candidate costs a few flops.
    Plane find_plane(const EventLists& ev, const Bounds3f& box, std::size_t n) const {
        Plane best;
        const Vec3f df = box.hi - box.lo;
        const double d[3] = {df.x, df.y, df.z};
        const double sa = 2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
        if (!(sa > 0.0)) {
            return best;
        }
        const double kt = cost_.kt, ki = cost_.ki;
        const double bonus = 1.0 - static_cast<double>(cost_.bonus);
        for (std::uint32_t k = 0; k < 3; ++k) {
            const double d1 = d[(k + 1) % 3], d2 = d[(k + 2) % 3];
            const double cap = 2.0 * d1 * d2 / sa, side = 2.0 * (d1 + d2) / sa;
            const double lo = box.lo[k], hi = box.hi[k];
            const std::vector<Event>& list = ev[k];
            std::size_t nl = 0, nr = n;
            std::size_t i = 0;
            const auto cost = [&](double pl, double pr, std::size_t l, std::size_t r) {
                const double c =
                    kt + ki * (pl * static_cast<double>(l) + pr * static_cast<double>(r));
                return l == 0 || r == 0 ? bonus * c : c;
            };
            while (i < list.size()) {
                const std::uint32_t pb = event_pos_bits(list[i]);
                std::size_t n_end = 0, n_planar = 0, n_start = 0;
                for (; i < list.size() && event_pos_bits(list[i]) == pb; ++i) {
                    const auto t = event_type(list[i]);
                    n_end += t == event_end ? 1 : 0;
                    n_planar += t == event_planar ? 1 : 0;
                    n_start += t == event_start ? 1 : 0;
                }
                nr -= n_planar + n_end;
                const float p = kd_detail::from_order_bits(pb);
                if (p > box.lo[k] && p < box.hi[k]) {
                    const double pl = cap + side * (static_cast<double>(p) - lo);
                    const double pr = cap + side * (hi - static_cast<double>(p));
                    const double cl = cost(pl, pr, nl + n_planar, nr);
                    const double cr = cost(pl, pr, nl, nr + n_planar);
                    if (cl < best.cost) {
                        best = {cl, k, p, true};
                    }
                    if (cr < best.cost) {
                        best = {cr, k, p, false};
                    }
                }
                nl += n_start + n_planar;
            }
        }
        return best;
    }

    /// Sets side[id] for the node's primitives from the events on the split axis.
    static void classify(const std::vector<Event>& list,
                         const std::vector<std::uint32_t>& ids,
                         const Plane& plane,
                         Side* side) {
        for (const std::uint32_t id : ids) {
            side[id] = side_both;
        }
        const float p = plane.pos;
        for (const Event e : list) {
            const float pos = event_pos(e);
            switch (event_type(e)) {
            case event_end:
                if (pos <= p) {
                    side[event_prim(e)] = side_left;
                }
                break;
            case event_start:
                if (pos >= p) {
                    side[event_prim(e)] = side_right;
                }
                break;
            default: {
                const bool left = pos < p || (pos == p && plane.planar_left);
                side[event_prim(e)] = left ? side_left : side_right;
            }
            }
        }
    }

    /// Splits the node's sorted lists into the children's, keeping them sorted.
    void split_lists(EventLists& ev,
                     const Plane& best,
                     const std::vector<std::uint32_t>& ids,
                     const Bounds3f& box,
                     const Side* side,
                     EventLists& left,
                     EventLists& right) const {
        const std::uint32_t a = best.axis;
        for (std::size_t k = 0; k < 3; ++k) {
            left[k].reserve(ev[k].size());
            right[k].reserve(ev[k].size());
            for (const Event e : ev[k]) {
                const Side s = side[event_prim(e)];
                if (s == side_left) {
                    left[k].push_back(e);
                } else if (s == side_right) {
                    right[k].push_back(e);
                } else if (!perfect_) {
                    // Cut at the plane: events off the split axis are kept on both sides; on
                    // it, the start stays left and the end right (new ones are added below).
                    if (k != a || event_type(e) == event_start) {
                        left[k].push_back(e);
                    }
                    if (k != a || event_type(e) == event_end) {
                        right[k].push_back(e);
                    }
                }
            }
            std::vector<Event>().swap(ev[k]);
        }
        EventLists both_left, both_right;
        for (const std::uint32_t id : ids) {
            if (side[id] != side_both) {
                continue;
            }
            if (!perfect_) {
                both_left[a].push_back(make_event(best.pos, event_end, id));
                both_right[a].push_back(make_event(best.pos, event_start, id));
                continue;
            }
            const Bounds3f left_box = kd_detail::half_box(box, a, best.pos, 0);
            const Bounds3f right_box = kd_detail::half_box(box, a, best.pos, 1);
            Bounds3f lb = intersection(in_.clip(id, left_box), left_box);
            Bounds3f rb = intersection(in_.clip(id, right_box), right_box);
            if (!is_usable_box(lb) && !is_usable_box(rb)) {
                // An inexact clip lost the primitive on both sides: keep its boxes instead.
                lb = intersection(in_.bounds[id], left_box);
                rb = intersection(in_.bounds[id], right_box);
            }
            if (is_usable_box(lb)) {
                add_events(both_left, id, lb);
            }
            if (is_usable_box(rb)) {
                add_events(both_right, id, rb);
            }
        }
        for (std::size_t k = 0; k < 3; ++k) {
            std::sort(both_left[k].begin(), both_left[k].end());
            std::sort(both_right[k].begin(), both_right[k].end());
            merge_sorted(left[k], both_left[k]);
            merge_sorted(right[k], both_right[k]);
        }
    }

    tbb::enumerable_thread_specific<std::unique_ptr<Side[]>> sides_;
};

KdTree build(const BuildInput& in, const KdTree::Config& cfg) {
    KdTree tree = kd_detail::start_tree(in, cfg);
    EventLists ev;
    for (std::size_t k = 0; k < 3; ++k) {
        ev[k].reserve(2 * in.bounds.size());
    }
    for (std::uint32_t id = 0; id < in.bounds.size(); ++id) {
        if (tree.prim_present[id]) {
            add_events(ev, id, in.bounds[id]);
        }
    }
    tbb::parallel_invoke([&] { kd_detail::sort_events(ev[0]); },
                         [&] { kd_detail::sort_events(ev[1]); },
                         [&] { kd_detail::sort_events(ev[2]); });
    SahBuilder builder(in, cfg, tree.max_depth);
    const bool parallel =
        tbb::this_task_arena::max_concurrency() > 1 &&
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
    Tree tasks({kd_detail::task_min, parallel, 0}, in.bounds.size());
    builder.build(tasks, tasks.root(), 0, std::move(ev), tree.scene_bounds, 0);
    kd_detail::splice(tasks, tree);
    return tree;
}

}  // namespace

/// The SAH kd-tree on cfg.threads TBB threads (0: all allowed); the tree does not depend on it.
KdTree build_kdtree_sah(const BuildInput& in, const KdTree::Config& cfg) {
    return with_threads(cfg.threads, [&] { return build(in, cfg); });
}

}  // namespace rtlab
