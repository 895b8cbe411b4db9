// Bvh: size and SAH figures, and the invariant check.

#include "accel/bvh/bvh.h"

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <vector>

namespace rtlab {

AccelInfo Bvh::info() const {
    AccelInfo i;
    i.nodes = nodes.size();
    i.bytes = nodes.size() * sizeof(BvhNode) + prim_ids.size() * sizeof(std::uint32_t);
    i.bytes_per_prim =
        prim_count == 0 ? 0.0 : static_cast<double>(i.bytes) / static_cast<double>(prim_count);
    i.refs_per_prim = prim_count == 0 ? 0.0 : 1.0;
    if (nodes.empty()) {
        return i;
    }
    const double ct = static_cast<double>(config.traversal_cost);
    const double ci = static_cast<double>(config.intersection_cost);
    const double root_area = static_cast<double>(nodes[0].bounds().surface_area());
    double cost = 0;
    struct Item {
        std::uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 0}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const BvhNode& n = nodes[it.node];
        const double area = static_cast<double>(n.bounds().surface_area());
        if (n.is_leaf()) {
            ++i.leaves;
            i.max_depth = std::max(i.max_depth, it.depth);
            cost += area * ci * static_cast<double>(n.prim_count());
        } else {
            cost += area * ct;
            stack.push_back({n.first, it.depth + 1});
            stack.push_back({n.first + 1, it.depth + 1});
        }
    }
    i.sah_cost = root_area > 0 ? cost / root_area : ci * static_cast<double>(prim_ids.size());
    return i;
}

std::string bvh_detail::check_prim_ids(std::span<const std::uint32_t> prim_ids,
                                       std::uint32_t prim_count,
                                       std::uint32_t unreferenced_count) {
    if (prim_ids.size() + unreferenced_count != prim_count) {
        return "prim_ids holds " + std::to_string(prim_ids.size()) + " ids, expected " +
               std::to_string(prim_count - unreferenced_count);
    }
    std::vector<char> seen(prim_count, 0);
    for (const std::uint32_t id : prim_ids) {
        if (id >= prim_count) {
            return "primitive id " + std::to_string(id) + " out of range";
        }
        if (seen[id]) {
            return "primitive " + std::to_string(id) + " referenced twice";
        }
        seen[id] = 1;
    }
    return {};
}

std::string Bvh::validate() const {
    if (std::string e = bvh_detail::check_prim_ids(prim_ids, prim_count, unreferenced_count);
        !e.empty()) {
        return e;
    }
    if (nodes.empty()) {
        return prim_ids.empty() ? std::string{} : "primitives but no nodes";
    }
    std::vector<char> slot_used(prim_ids.size(), 0);
    std::vector<char> node_seen(nodes.size(), 0);
    struct Item {
        std::uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 0}};
    std::size_t visited = 0;
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const std::string where = "node " + std::to_string(it.node) + ": ";
        if (node_seen[it.node]) {
            return where + "reached twice";
        }
        node_seen[it.node] = 1;
        ++visited;
        if (it.depth > 64) {
            return where + "depth " + std::to_string(it.depth) + " > 64";
        }
        const BvhNode& n = nodes[it.node];
        const Bounds3f box = n.bounds();
        if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z)) {
            return where + "empty or NaN box";
        }
        if (n.is_leaf()) {
            if (n.prim_count() > config.max_leaf_size) {
                return where + "leaf of " + std::to_string(n.prim_count()) + " > max_leaf_size";
            }
            if (n.first > prim_ids.size() || n.prim_count() > prim_ids.size() - n.first) {
                return where + "leaf range outside prim_ids";
            }
            for (std::uint32_t s = n.first; s < n.first + n.prim_count(); ++s) {
                if (slot_used[s]) {
                    return where + "prim_ids slot " + std::to_string(s) + " in two leaves";
                }
                slot_used[s] = 1;
            }
            continue;
        }
        if (n.axis() > 2) {
            return where + "split axis > 2";
        }
        if (n.first <= it.node || n.first + 1 >= nodes.size()) {
            return where + "children not after the parent or out of range";
        }
        for (std::uint32_t c = n.first; c <= n.first + 1; ++c) {
            if (!box.contains(nodes[c].bounds())) {
                return where + "child " + std::to_string(c) + " outside its parent";
            }
            stack.push_back({c, it.depth + 1});
        }
    }
    if (visited != nodes.size()) {
        return std::to_string(nodes.size() - visited) + " nodes unreachable";
    }
    if (std::find(slot_used.begin(), slot_used.end(), 0) != slot_used.end()) {
        return "a prim_ids slot lies in no leaf";
    }
    return {};
}

}  // namespace rtlab
