// collapse_bvh: a binary BVH into a BVH4, BVH8 or BVH16. Each wide node starts from a binary node's
// two children and repeatedly opens the inner child of largest surface area (the one a random ray
// reaches most often, so opening it saves the most node visits under the SAH) until it holds N
// children or only leaves (greedy SAH collapse as in Wald, Benthin & Boulos 2008 and Embree's
// BVH4/8 builders). With ChildOrder::area the children are then sorted by surface area, largest
// first (the order any-hit traversal visits them in). Leaves and their prim_ids slots are kept as
// the binary build made them. The subtrees below the top levels are collapsed in parallel (TBB),
// the same nodes for any threads.

#include "accel/bvh/build_common.h"
#include "accel/bvh/wide_bvh.h"

#include <array>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// The binary nodes that become the children of a wide node, at most N (no heap: this runs once
/// per wide node).
template <unsigned N>
struct Kids {
    std::array<std::uint32_t, N> node{};
    std::array<float, N> area{};  ///< surface area of the kid's box
    unsigned size = 0;

    /// Kid i becomes binary node b.
    void set(const Bvh& bvh, unsigned i, std::uint32_t b) {
        node[i] = b;
        area[i] = bvh.nodes[b].bounds().surface_area();
    }
    void add(const Bvh& bvh, std::uint32_t b) { set(bvh, size++, b); }
};

/// The kids of the wide node for binary node `b`: its two children, then the inner kid of
/// largest surface area opened (replaced by its first child, its second appended) until there
/// are N or only leaves (ties keep the first); with ChildOrder::area then sorted by surface area,
/// largest first (stable).
template <unsigned N>
Kids<N> wide_children(const Bvh& bvh, std::uint32_t b, ChildOrder order) {
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
            if (!bvh.nodes[kids.node[i]].is_leaf() && kids.area[i] > best_area) {
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
    if (order == ChildOrder::area) {
        for (unsigned i = 1; i < kids.size; ++i) {  // insertion sort: at most N kids
            for (unsigned j = i; j > 0 && kids.area[j] > kids.area[j - 1]; --j) {
                std::swap(kids.node[j], kids.node[j - 1]);
                std::swap(kids.area[j], kids.area[j - 1]);
            }
        }
    }
    return kids;
}

/// Fills wide node nodes[it.target] from the kids of binary node it.source, appending a fresh
/// wide node to `nodes` for every inner kid and pushing it (bvh_detail::convert_tree's expand).
template <unsigned N, class Push>
void expand(const Bvh& bvh,
            const bvh_detail::ConvertItem& it,
            LargeVector<WideNode<N>>& nodes,
            const Push& push,
            ChildOrder order) {
    const Kids<N> kids = wide_children<N>(bvh, it.source, order);
    for (unsigned i = 0; i < kids.size; ++i) {
        const BvhNode& k = bvh.nodes[kids.node[i]];
        if (k.is_leaf()) {
            nodes[it.target].set(i, k.bounds(), k.first, k.prim_count());
        } else {
            const auto child = static_cast<std::uint32_t>(nodes.size());
            nodes.push_back(WideNode<N>::empty());
            nodes[it.target].set(i, k.bounds(), child, 0);
            push({kids.node[i], child, it.depth + 1});
        }
    }
}

}  // namespace

template <unsigned N>
WideBvh<N> collapse_bvh(Bvh bvh, ChildOrder order) {
    WideBvh<N> w;
    w.prim_ids = std::move(bvh.prim_ids);  // the nodes below never read them
    w.prim_count = bvh.prim_count;
    w.unreferenced_count = bvh.unreferenced_count;
    w.config = bvh.config;
    if (bvh.nodes.empty()) {
        return w;
    }
    // The top levels serially, down to the wide depth with up to 64 nodes (N^depth; 16 for
    // BVH16), each subtree below them by its own task.
    constexpr std::uint32_t task_depth = N == 16 ? 1 : N == 8 ? 2 : 3;
    bvh_detail::convert_tree(
        w.nodes, WideNode<N>::empty(), task_depth,
        [&](const bvh_detail::ConvertItem& it, LargeVector<WideNode<N>>& out, const auto& push) {
            expand<N>(bvh, it, out, push, order);
        },
        [](WideNode<N> n, const auto& map) {
            for (unsigned i = 0; i < N; ++i) {
                if (n.occupied(i) && n.count[i] == 0) {
                    n.child[i] = map(n.child[i]);
                }
            }
            return n;
        });
    return w;
}

template WideBvh<4> collapse_bvh<4>(Bvh, ChildOrder);
template WideBvh<8> collapse_bvh<8>(Bvh, ChildOrder);
template WideBvh<16> collapse_bvh<16>(Bvh, ChildOrder);

}  // namespace rtlab
