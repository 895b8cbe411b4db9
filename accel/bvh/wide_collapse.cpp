// collapse_bvh: a binary BVH into a BVH4 or BVH8. Each wide node starts from a binary node's two
// children and repeatedly opens the inner child of largest surface area (the one a random ray
// reaches most often, so opening it saves the most node visits under the SAH) until it holds N
// children or only leaves (greedy SAH collapse as in Wald, Benthin & Boulos 2008 and Embree's
// BVH4/8 builders). Leaves and their prim_ids slots are kept as the binary build made them.

#include "accel/bvh/wide_bvh.h"

#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// The binary nodes that become the children of the wide node for binary node `b`.
template <unsigned N>
std::vector<std::uint32_t> wide_children(const Bvh& bvh, std::uint32_t b) {
    const BvhNode& node = bvh.nodes[b];
    if (node.is_leaf()) {
        return {b};  // only for the root: a wide root holding the single leaf
    }
    std::vector<std::uint32_t> kids{node.first, node.first + 1};
    while (kids.size() < N) {
        std::size_t best = kids.size();
        float best_area = -1.0f;
        for (std::size_t i = 0; i < kids.size(); ++i) {
            const BvhNode& k = bvh.nodes[kids[i]];
            const float area = k.bounds().surface_area();
            if (!k.is_leaf() && area > best_area) {
                best = i;
                best_area = area;
            }
        }
        if (best == kids.size()) {
            break;  // only leaves left
        }
        const std::uint32_t opened = bvh.nodes[kids[best]].first;
        kids[best] = opened;
        kids.push_back(opened + 1);
    }
    return kids;
}

}  // namespace

template <unsigned N>
WideBvh<N> collapse_bvh(const Bvh& bvh) {
    WideBvh<N> w;
    w.prim_ids = bvh.prim_ids;
    w.prim_count = bvh.prim_count;
    w.unreferenced_count = bvh.unreferenced_count;
    w.config = bvh.config;
    if (bvh.nodes.empty()) {
        return w;
    }
    // Depth-first: (binary node, wide node) pairs still to fill.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0, 0}};
    w.nodes.push_back(WideNode<N>::empty());
    while (!todo.empty()) {
        const auto [b, wi] = todo.back();
        todo.pop_back();
        const std::vector<std::uint32_t> kids = wide_children<N>(bvh, b);
        for (unsigned i = 0; i < kids.size(); ++i) {
            const BvhNode& k = bvh.nodes[kids[i]];
            if (k.is_leaf()) {
                w.nodes[wi].set(i, k.bounds(), k.first, k.prim_count());
            } else {
                const auto child = static_cast<std::uint32_t>(w.nodes.size());
                w.nodes.push_back(WideNode<N>::empty());
                w.nodes[wi].set(i, k.bounds(), child, 0);
                todo.emplace_back(kids[i], child);
            }
        }
    }
    return w;
}

template WideBvh<4> collapse_bvh<4>(const Bvh&);
template WideBvh<8> collapse_bvh<8>(const Bvh&);

}  // namespace rtlab
