// WideBvh: bounds, size and SAH figures, and the invariant check.

#include "accel/bvh/wide_bvh.h"

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace rtlab {

template <unsigned N>
Bounds3f WideBvh<N>::bounds() const {
    Bounds3f b;
    if (!nodes.empty()) {
        for (unsigned i = 0; i < N && nodes[0].occupied(i); ++i) {
            b.extend(nodes[0].bounds(i));
        }
    }
    return b;
}

template <unsigned N>
AccelInfo WideBvh<N>::info() const {
    AccelInfo info = bvh_detail::size_info(
        nodes.size(),
        nodes.size() * sizeof(WideNode<N>) + qnodes.size() * sizeof(QWideNode8) +
            diags.size() * sizeof(WideDiag<N>) + prim_ids.size() * sizeof(std::uint32_t),
        prim_count, prim_ids, unreferenced_count);
    if (nodes.empty()) {
        return info;
    }
    bvh_detail::SahTally sah(config, bounds());
    sah.inner(bounds());  // the root node itself
    bvh_detail::walk_from_root([&](std::uint32_t node, std::uint32_t depth, const auto& push) {
        const WideNode<N>& n = nodes[node];
        for (unsigned i = 0; i < N && n.occupied(i); ++i) {
            if (n.is_leaf(i)) {
                sah.leaf(n.bounds(i), n.count[i], depth + 1);
            } else {
                sah.inner(n.bounds(i));
                push(n.child[i], depth + 1);
            }
        }
    });
    sah.finish(info, prim_ids.size());
    return info;
}

template <unsigned N>
std::string WideBvh<N>::validate() const {
    if (auto v = bvh_detail::check_before_nodes(prim_ids, prim_count, unreferenced_count,
                                                nodes.size())) {
        return *v;
    }
    std::vector<char> slot_used(prim_ids.size(), 0);
    struct Item {
        std::uint32_t node, depth;
        Bounds3f box;  // the parent slot's box (everything for the root)
    };
    const auto check = [&](const Item& it, const std::string& where, auto& push) -> std::string {
        const WideNode<N>& n = nodes[it.node];
        unsigned used = 0;
        for (unsigned i = 0; i < N; ++i) {
            const std::string slot = where + "slot " + std::to_string(i) + ": ";
            const Bounds3f box = n.bounds(i);
            if (!n.occupied(i)) {
                if (n.count[i] != 0 || !(box == Bounds3f{})) {
                    return slot + "empty slot with a count or a box";
                }
                continue;
            }
            if (used != i) {
                return slot + "occupied after an empty slot";
            }
            ++used;
            if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z)) {
                return slot + "empty or NaN box";
            }
            if (!it.box.contains(box)) {
                return slot + "box outside its parent's";
            }
            if (n.is_leaf(i)) {
                const std::uint32_t first = n.child[i], count = n.count[i];
                if (count > config.max_leaf_size) {
                    return slot + "leaf of " + std::to_string(count) + " > max_leaf_size";
                }
                if (std::string e = bvh_detail::use_leaf_slots(prim_ids, slot_used, first, count);
                    !e.empty()) {
                    return slot + e;
                }
            } else {
                if (n.child[i] <= it.node || n.child[i] >= nodes.size()) {
                    return slot + "child not after the parent or out of range";
                }
                push({n.child[i], it.depth + 1, box});
            }
        }
        if (used < (it.node == 0 ? 1u : 2u)) {
            return where + std::to_string(used) + " children";
        }
        return {};
    };
    const float inf = std::numeric_limits<float>::infinity();
    const Item root{0, 0, {{-inf, -inf, -inf}, {inf, inf, inf}}};
    if (std::string e = bvh_detail::check_from_root(nodes.size(), root, check); !e.empty()) {
        return e;
    }
    if (std::string e = validate_quantized(); !e.empty()) {
        return e;
    }
    if (std::string e = validate_diags(); !e.empty()) {
        return e;
    }
    return bvh_detail::check_slots_covered(prim_ids, slot_used);
}

template <unsigned N>
std::string WideBvh<N>::validate_quantized() const {
    if (qnodes.empty()) {
        return {};
    }
    if (N != 8 || qnodes.size() != nodes.size()) {
        return "quantised nodes: " + std::to_string(qnodes.size()) + " for " +
               std::to_string(nodes.size()) + " nodes of width " + std::to_string(N);
    }
    for (std::size_t k = 0; k < nodes.size(); ++k) {
        const WideNode<N>& n = nodes[k];
        const QWideNode8& q = qnodes[k];
        for (unsigned i = 0; i < N; ++i) {
            const std::string slot =
                "quantised node " + std::to_string(k) + " slot " + std::to_string(i) + ": ";
            const bool occupied = ((q.occupied >> i) & 1u) != 0;
            if (occupied != n.occupied(i) || q.child[i] != n.child[i] || q.count[i] != n.count[i]) {
                return slot + "child, count or occupancy differs from the node's";
            }
            if (occupied && !q.bounds(i).contains(n.bounds(i))) {
                return slot + "dequantised box does not enclose the node's box";
            }
        }
    }
    return {};
}

template struct WideBvh<4>;
template struct WideBvh<8>;
template struct WideBvh<16>;

}  // namespace rtlab
