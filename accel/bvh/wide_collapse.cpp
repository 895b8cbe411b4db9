// collapse_bvh: a binary BVH into a BVH4 or BVH8. Each wide node starts from a binary node's two
// children and repeatedly opens the inner child of largest surface area (the one a random ray
// reaches most often, so opening it saves the most node visits under the SAH) until it holds N
// children or only leaves (greedy SAH collapse as in Wald, Benthin & Boulos 2008 and Embree's
// BVH4/8 builders). Leaves and their prim_ids slots are kept as the binary build made them.

#include "accel/bvh/wide_bvh.h"

#include <array>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// The binary nodes that become the children of a wide node, at most N (no heap: this runs once
/// per wide node, serially).
template <unsigned N>
struct Kids {
    std::array<std::uint32_t, N> node{};
    std::array<float, N> area{};  ///< surface area of an inner kid; -1 for a leaf
    unsigned size = 0;

    /// Kid i becomes binary node b.
    void set(const Bvh& bvh, unsigned i, std::uint32_t b) {
        const BvhNode& k = bvh.nodes[b];
        node[i] = b;
        area[i] = k.is_leaf() ? -1.0f : k.bounds().surface_area();
    }
    void add(const Bvh& bvh, std::uint32_t b) { set(bvh, size++, b); }
};

/// The kids of the wide node for binary node `b`: its two children, then the inner kid of
/// largest surface area opened (replaced by its first child, its second appended) until there
/// are N or only leaves (ties keep the first).
template <unsigned N>
Kids<N> wide_children(const Bvh& bvh, std::uint32_t b) {
    Kids<N> kids;
    const BvhNode& node = bvh.nodes[b];
    if (node.is_leaf()) {
        kids.add(bvh, b);  // only for the root: a wide root holding the single leaf
        return kids;
    }
    kids.add(bvh, node.first);
    kids.add(bvh, node.first + 1);
    while (kids.size < N) {
        unsigned best = kids.size;
        float best_area = -1.0f;
        for (unsigned i = 0; i < kids.size; ++i) {
            if (kids.area[i] > best_area) {
                best = i;
                best_area = kids.area[i];
            }
        }
        if (best == kids.size) {
            break;  // only leaves left
        }
        const std::uint32_t opened = bvh.nodes[kids.node[best]].first;
        kids.set(bvh, best, opened);
        kids.add(bvh, opened + 1);
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
        const Kids<N> kids = wide_children<N>(bvh, b);
        for (unsigned i = 0; i < kids.size; ++i) {
            const BvhNode& k = bvh.nodes[kids.node[i]];
            if (k.is_leaf()) {
                w.nodes[wi].set(i, k.bounds(), k.first, k.prim_count());
            } else {
                const auto child = static_cast<std::uint32_t>(w.nodes.size());
                w.nodes.push_back(WideNode<N>::empty());
                w.nodes[wi].set(i, k.bounds(), child, 0);
                todo.emplace_back(kids.node[i], child);
            }
        }
    }
    return w;
}

template WideBvh<4> collapse_bvh<4>(const Bvh&);
template WideBvh<8> collapse_bvh<8>(const Bvh&);

}  // namespace rtlab
