// SAH kd-tree in O(N log N): Wald & Havran 2006, "On building fast kd-trees for ray tracing, and
// on doing that in O(N log N)". Per-axis event lists (end < planar < start at equal positions) are
// sorted once; each node sweeps them to find the cheapest plane (planar primitives go to the
// cheaper side), classifies primitives left / right / both, and splits the lists in linear time;
// only the clipped events of straddling primitives are sorted and merged back in. Planes on the
// node's boundary are not candidates (they would repeat the node). Perfect splits: a straddling
// primitive's part on each side is BuildInput::clip(id, side box) when given, else box ∩ side.

#include "accel/kdtree/build_common.h"
#include "accel/kdtree/kdtree.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace rtlab {

namespace {

/// Event kinds, in the order they sort at equal positions.
enum EventType : std::uint8_t { event_end = 0, event_planar = 1, event_start = 2 };

/// One boundary of a primitive's clipped box along one axis.
struct Event {
    float pos;
    std::uint32_t prim;
    std::uint8_t type;

    friend bool operator<(const Event& a, const Event& b) {
        if (a.pos != b.pos) {
            return a.pos < b.pos;
        }
        if (a.type != b.type) {
            return a.type < b.type;
        }
        return a.prim < b.prim;
    }
};

using EventLists = std::array<std::vector<Event>, 3>;

/// Appends the events of `box` (non-empty) for primitive `id` on every axis.
void add_events(EventLists& ev, std::uint32_t id, const Bounds3f& box) {
    for (std::size_t k = 0; k < 3; ++k) {
        if (box.lo[k] == box.hi[k]) {
            ev[k].push_back({box.lo[k], id, event_planar});
        } else {
            ev[k].push_back({box.lo[k], id, event_start});
            ev[k].push_back({box.hi[k], id, event_end});
        }
    }
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

class SahBuilder {
public:
    SahBuilder(const BuildInput& in, const KdTree::Config& cfg, KdTree& tree)
        : in_(in)
        , cost_{cfg.traversal_cost, cfg.intersection_cost, cfg.empty_bonus}
        , min_leaf_(cfg.min_leaf_size)
        , tree_(tree)
        , side_(in.bounds.size(), side_both) {}

    /// Builds the subtree of the node `box` whose primitives' events are `ev`.
    void recurse(EventLists ev, const Bounds3f& box, std::uint32_t depth) {
        std::vector<std::uint32_t> ids;
        for (const Event& e : ev[0]) {
            if (e.type != event_end) {
                ids.push_back(e.prim);
            }
        }
        const std::size_t n = ids.size();
        if (n <= min_leaf_ || depth >= tree_.max_depth) {
            kd_detail::emit_leaf(tree_, ids);
            return;
        }
        const Plane best = find_plane(ev, box, n);
        if (!(best.cost < cost_.leaf_cost(n))) {
            kd_detail::emit_leaf(tree_, ids);
            return;
        }
        const Bounds3f left_box = kd_detail::half_box(box, best.axis, best.pos, 0);
        const Bounds3f right_box = kd_detail::half_box(box, best.axis, best.pos, 1);
        classify(ev[best.axis], ids, best);

        // Split the sorted lists: one-sided primitives keep their events (order is preserved).
        EventLists left, right;
        for (std::size_t k = 0; k < 3; ++k) {
            for (const Event& e : ev[k]) {
                if (side_[e.prim] == side_left) {
                    left[k].push_back(e);
                } else if (side_[e.prim] == side_right) {
                    right[k].push_back(e);
                }
            }
            ev[k].clear();
            ev[k].shrink_to_fit();
        }
        // Straddling primitives get new events from their clipped parts, sorted and merged.
        EventLists both_left, both_right;
        for (const std::uint32_t id : ids) {
            if (side_[id] != side_both) {
                continue;
            }
            Bounds3f lb = clip(id, left_box), rb = clip(id, right_box);
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
        merge_into(left, both_left);
        merge_into(right, both_right);

        const std::uint32_t index = kd_detail::emit_inner(tree_, best.axis, best.pos);
        recurse(std::move(left), left_box, depth + 1);
        kd_detail::link_above(tree_, index);
        recurse(std::move(right), right_box, depth + 1);
    }

private:
    /// The sweep over the three sorted event lists (Wald & Havran, algorithm 4).
    Plane find_plane(const EventLists& ev, const Bounds3f& box, std::size_t n) const {
        Plane best;
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::vector<Event>& list = ev[k];
            std::size_t nl = 0, nr = n;
            std::size_t i = 0;
            while (i < list.size()) {
                const float p = list[i].pos;
                std::size_t n_end = 0, n_planar = 0, n_start = 0;
                while (i < list.size() && list[i].pos == p && list[i].type == event_end) {
                    ++n_end;
                    ++i;
                }
                while (i < list.size() && list[i].pos == p && list[i].type == event_planar) {
                    ++n_planar;
                    ++i;
                }
                while (i < list.size() && list[i].pos == p && list[i].type == event_start) {
                    ++n_start;
                    ++i;
                }
                nr -= n_planar + n_end;
                if (p > box.lo[k] && p < box.hi[k]) {
                    const double cl = cost_.split_cost(box, k, p, nl + n_planar, nr);
                    const double cr = cost_.split_cost(box, k, p, nl, nr + n_planar);
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

    /// Sets side_[id] for the node's primitives from the events on the split axis.
    void classify(const std::vector<Event>& list,
                  const std::vector<std::uint32_t>& ids,
                  const Plane& plane) {
        for (const std::uint32_t id : ids) {
            side_[id] = side_both;
        }
        const float p = plane.pos;
        for (const Event& e : list) {
            if (e.type == event_end && e.pos <= p) {
                side_[e.prim] = side_left;
            } else if (e.type == event_start && e.pos >= p) {
                side_[e.prim] = side_right;
            } else if (e.type == event_planar) {
                const bool left = e.pos < p || (e.pos == p && plane.planar_left);
                side_[e.prim] = left ? side_left : side_right;
            }
        }
    }

    /// The part of primitive id inside box (empty when none).
    Bounds3f clip(std::uint32_t id, const Bounds3f& box) const {
        if (in_.clip) {
            return intersection(in_.clip(id, box), box);
        }
        return intersection(in_.bounds[id], box);
    }

    /// Sorts `extra` and merges it into the already sorted `lists`, axis by axis.
    static void merge_into(EventLists& lists, EventLists& extra) {
        for (std::size_t k = 0; k < 3; ++k) {
            if (extra[k].empty()) {
                continue;
            }
            std::sort(extra[k].begin(), extra[k].end());
            std::vector<Event> merged(lists[k].size() + extra[k].size());
            std::merge(lists[k].begin(), lists[k].end(), extra[k].begin(), extra[k].end(),
                       merged.begin());
            lists[k] = std::move(merged);
        }
    }

    const BuildInput& in_;
    kd_detail::CostModel cost_;
    std::size_t min_leaf_;
    KdTree& tree_;
    std::vector<std::uint8_t> side_;  ///< per primitive id, valid for the node being split
};

}  // namespace

KdTree build_kdtree_sah(const BuildInput& in, const KdTree::Config& cfg) {
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
    for (std::size_t k = 0; k < 3; ++k) {
        std::sort(ev[k].begin(), ev[k].end());
    }
    SahBuilder builder(in, cfg, tree);
    builder.recurse(std::move(ev), tree.scene_bounds, 0);
    return tree;
}

}  // namespace rtlab
