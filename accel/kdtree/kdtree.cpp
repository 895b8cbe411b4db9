// kd-tree: size and SAH figures, and the structural invariants.

#include "accel/kdtree/kdtree.h"

#include "accel/kdtree/build_common.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rtlab {

namespace {

/// Walks the tree with node boxes; calls fn(node_index, box, depth) for every node.
template <class Fn>
void walk(const KdTree& t, Fn&& fn) {
    if (t.nodes.empty()) {
        return;
    }
    struct Item {
        std::uint32_t node;
        Bounds3f box;
        std::uint32_t depth;
    };
    std::vector<Item> todo{{0, t.scene_bounds, 0}};
    while (!todo.empty()) {
        const Item it = todo.back();
        todo.pop_back();
        if (!fn(it.node, it.box, it.depth)) {
            continue;
        }
        const KdNode& n = t.nodes[it.node];
        if (!n.is_leaf()) {
            todo.push_back({n.above_child(), kd_detail::half_box(it.box, n.axis(), n.split(), 1),
                            it.depth + 1});
            todo.push_back(
                {it.node + 1, kd_detail::half_box(it.box, n.axis(), n.split(), 0), it.depth + 1});
        }
    }
}

}  // namespace

AccelInfo KdTree::info() const {
    AccelInfo i;
    i.nodes = nodes.size();
    i.bytes = nodes.size() * sizeof(KdNode) + prim_ids.size() * sizeof(std::uint32_t);
    std::size_t present = 0;
    for (const bool p : prim_present) {
        present += p ? 1 : 0;
    }
    const double root_area = static_cast<double>(scene_bounds.surface_area());
    double cost = 0;
    walk(*this, [&](std::uint32_t index, const Bounds3f& box, std::uint32_t depth) {
        const KdNode& n = nodes[index];
        const double p = root_area > 0 ? static_cast<double>(box.surface_area()) / root_area : 1.0;
        if (n.is_leaf()) {
            ++i.leaves;
            i.max_depth = std::max(i.max_depth, depth);
            cost +=
                static_cast<double>(intersection_cost) * static_cast<double>(n.prim_count()) * p;
        } else {
            cost += static_cast<double>(traversal_cost) * p;
        }
        return true;
    });
    i.sah_cost = cost;
    if (present > 0) {
        i.bytes_per_prim = static_cast<double>(i.bytes) / static_cast<double>(present);
        i.refs_per_prim = static_cast<double>(prim_ids.size()) / static_cast<double>(present);
    }
    return i;
}

std::string KdTree::validate() const {
    if (nodes.empty()) {
        for (const bool p : prim_present) {
            if (p) {
                return "no nodes although primitives are present";
            }
        }
        return {};
    }
    std::string error;
    std::vector<bool> seen(prim_present.size());
    std::size_t visited = 0;
    walk(*this, [&](std::uint32_t index, const Bounds3f& box, std::uint32_t depth) {
        if (!error.empty()) {
            return false;
        }
        ++visited;
        const std::string where = "node " + std::to_string(index) + ": ";
        if (depth > max_depth) {
            error = where + "depth " + std::to_string(depth) + " exceeds max_depth";
            return false;
        }
        const KdNode& n = nodes[index];
        if (n.is_leaf()) {
            if (static_cast<std::size_t>(n.prim_offset()) + n.prim_count() > prim_ids.size()) {
                error = where + "leaf list out of range";
                return false;
            }
            for (std::uint32_t k = 0; k < n.prim_count(); ++k) {
                const std::uint32_t id = prim_ids[n.prim_offset() + k];
                if (id >= prim_present.size() || !prim_present[id]) {
                    error = where + "leaf references missing primitive " + std::to_string(id);
                    return false;
                }
                seen[id] = true;
            }
            return false;
        }
        const std::uint32_t a = n.axis();
        if (!(n.split() >= box.lo[a] && n.split() <= box.hi[a])) {
            error = where + "split outside the node's box";
            return false;
        }
        if (index + 1 >= nodes.size() || n.above_child() <= index + 1 ||
            n.above_child() >= nodes.size()) {
            error = where + "child index out of range";
            return false;
        }
        return true;
    });
    if (!error.empty()) {
        return error;
    }
    if (visited != nodes.size()) {
        return "nodes unreachable from the root or shared: visited " + std::to_string(visited) +
               " of " + std::to_string(nodes.size());
    }
    for (std::size_t id = 0; id < prim_present.size(); ++id) {
        if (prim_present[id] && !seen[id]) {
            return "primitive " + std::to_string(id) + " is in no leaf";
        }
    }
    return {};
}

}  // namespace rtlab
