// collapse_bvh: a binary BVH into a BVH4, BVH8 or BVH16, by one of two rules (WideCollapse).
// greedy: each wide node starts from a binary node's two children and repeatedly opens the inner
// child of largest surface area (the one a random ray reaches most often, so opening it saves the
// most node visits under the SAH) until it holds N children or only leaves (greedy SAH collapse as
// in Wald, Benthin & Boulos 2008 and Embree's BVH4/8 builders). sah: dynamic programming over the
// binary tree (SahCollapse) gives the wide nodes of least summed surface area. With
// ChildOrder::area the children are then sorted by surface area, largest first (the order any-hit
// traversal visits them in). Leaves and their prim_ids slots are kept as the binary build made
// them. The subtrees below the top levels are collapsed in parallel (TBB), the same nodes for any
// threads.

#include "accel/bvh/build_common.h"
#include "accel/bvh/wide_bvh.h"
#include "base/scratch_vector.h"

#include <algorithm>
#include <array>
#include <optional>
#include <tbb/parallel_invoke.h>
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

/// The kids of the wide node for binary node `b` by the greedy rule: its two children, then the
/// inner kid of largest surface area opened (replaced by its first child, its second appended)
/// until there are N or only leaves (ties keep the first).
template <unsigned N>
Kids<N> greedy_children(const Bvh& bvh, std::uint32_t b) {
    Kids<N> kids;
    const BvhNode& node = bvh.nodes[b];
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
    return kids;
}

/// The sah rule (Ylitie, Karras & Laine 2017, section 4.1, leaves kept): for binary node b and
/// i = 1..N, the least summed surface area of the wide nodes that hold b's subtree as at most i
/// kids of the wide node above is either b itself as one kid (its own wide node: its area plus the
/// best split of N kids between its children; a leaf: 0) or the best split of i kids between its
/// children. Nodes are solved children first (the top levels by tasks, each subtree below them by
/// one loop; the same choices for any threads); each keeps only its choices, its costs live until
/// its parent is solved.
template <unsigned N>
class SahCollapse {
public:
    explicit SahCollapse(const Bvh& bvh) : bvh_(bvh), choices_(bvh.nodes.size()) {
        solve_subtree(0, 0);
    }

    /// The kids of the wide node for inner binary node b: its own split of N kids.
    Kids<N> children(std::uint32_t b) const {
        Kids<N> kids;
        const std::uint32_t left = bvh_.nodes[b].first;
        gather(left, choices_[b].own_left, kids);
        gather(left + 1, N - choices_[b].own_left, kids);
        return kids;
    }

private:
    /// What is kept of binary node b.
    struct Choice {
        std::array<std::uint8_t, N> split;  ///< split[i - 1]: kids the left child takes of at most
                                            ///< i; 0: b is one kid
        std::uint8_t own_left;              ///< kids the left child takes in b's own wide node
    };
    /// A solved subtree's costs: cost[i - 1] the least with at most i kids; and its leaves (at
    /// most N: more kids than leaves cost what as many as its leaves do).
    struct Costs {
        std::array<float, N> cost;
        unsigned leaves;
    };

    /// The kids holding binary node b's subtree as at most i of them, appended to kids.
    void gather(std::uint32_t b, unsigned i, Kids<N>& kids) const {
        const unsigned k = choices_[b].split[i - 1];
        if (k == 0) {
            kids.add(bvh_, b);
            return;
        }
        gather(bvh_.nodes[b].first, k, kids);
        gather(bvh_.nodes[b].first + 1, i - k, kids);
    }

    /// Solves b's subtree: above depth 6 (64 subtrees) its children by two tasks, below by a
    /// post-order loop without recursion (a binary tree may be deep) whose stack holds the costs
    /// of the subtrees solved and not yet combined.
    Costs solve_subtree(std::uint32_t b, unsigned depth) {
        const BvhNode& node = bvh_.nodes[b];
        if (!node.is_leaf() && depth < 6) {
            Costs l, r;
            tbb::parallel_invoke([&] { l = solve_subtree(node.first, depth + 1); },
                                 [&] { r = solve_subtree(node.first + 1, depth + 1); });
            return solve(b, l, r);
        }
        std::vector<std::pair<std::uint32_t, bool>> todo{{b, false}};
        std::vector<Costs> solved;
        while (!todo.empty()) {
            const auto [n, children_solved] = todo.back();
            todo.pop_back();
            const BvhNode& nn = bvh_.nodes[n];
            if (nn.is_leaf()) {
                solved.push_back(solve_leaf(n));
            } else if (children_solved) {
                const Costs r = solved.back();
                solved.pop_back();
                solved.back() = solve(n, solved.back(), r);
            } else {
                todo.push_back({n, true});
                todo.push_back({nn.first + 1, false});
                todo.push_back({nn.first, false});
            }
        }
        return solved.back();
    }

    /// Leaf b: one kid at no cost, whatever the kids allowed.
    Costs solve_leaf(std::uint32_t b) {
        choices_[b].split.fill(0);
        choices_[b].own_left = 0;
        Costs out;
        out.cost.fill(0.0f);
        out.leaves = 1;
        return out;
    }

    /// Inner node b's choices from its children's costs l and r; returns its costs.
    Costs solve(std::uint32_t b, const Costs& l, const Costs& r) {
        Choice& choice = choices_[b];
        Costs out;
        out.leaves = std::min(l.leaves + r.leaves, N);
        // split_cost[j - 1]: the best split of j >= 2 kids, k of them to the left child (the
        // first k of least cost: a comparison that fails on a NaN keeps the first k tried).
        std::array<float, N> split_cost{};
        std::array<std::uint8_t, N> split_k{};
        for (unsigned j = 2; j <= out.leaves; ++j) {
            const unsigned k_lo = j > r.leaves ? j - r.leaves : 1;
            const unsigned k_hi = std::min(j - 1, l.leaves);
            split_cost[j - 1] = l.cost[k_lo - 1] + r.cost[j - k_lo - 1];
            split_k[j - 1] = static_cast<std::uint8_t>(k_lo);
            for (unsigned k = k_lo + 1; k <= k_hi; ++k) {
                const float c = l.cost[k - 1] + r.cost[j - k - 1];
                if (c < split_cost[j - 1]) {
                    split_cost[j - 1] = c;
                    split_k[j - 1] = static_cast<std::uint8_t>(k);
                }
            }
        }
        for (unsigned j = out.leaves + 1; j <= N; ++j) {
            split_cost[j - 1] = split_cost[j - 2];
            split_k[j - 1] = split_k[j - 2];
        }
        const float own = bvh_.nodes[b].bounds().surface_area() + split_cost[N - 1];
        choice.own_left = split_k[N - 1];
        out.cost[0] = own;
        choice.split[0] = 0;
        for (unsigned i = 2; i <= N; ++i) {
            const bool split = split_cost[i - 1] < own;
            out.cost[i - 1] = split ? split_cost[i - 1] : own;
            choice.split[i - 1] = split ? split_k[i - 1] : 0;
        }
        return out;
    }

    const Bvh& bvh_;
    ScratchVector<Choice> choices_;
};

/// With ChildOrder::area, kids sorted by surface area, largest first (stable).
template <unsigned N>
void order_kids(Kids<N>& kids, ChildOrder order) {
    if (order == ChildOrder::area) {
        for (unsigned i = 1; i < kids.size; ++i) {  // insertion sort: at most N kids
            for (unsigned j = i; j > 0 && kids.area[j] > kids.area[j - 1]; --j) {
                std::swap(kids.node[j], kids.node[j - 1]);
                std::swap(kids.area[j], kids.area[j - 1]);
            }
        }
    }
}

/// Fills wide node nodes[it.target] from `kids`, the kids of binary node it.source, appending a
/// fresh wide node to `nodes` for every inner kid and pushing it (bvh_detail::convert_tree's
/// expand).
template <unsigned N, class Push>
void expand(const Bvh& bvh,
            const bvh_detail::ConvertItem& it,
            const Kids<N>& kids,
            LargeVector<WideNode<N>>& nodes,
            const Push& push) {
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
WideBvh<N> collapse_bvh(Bvh bvh, ChildOrder order, WideCollapse rule) {
    WideBvh<N> w;
    bvh_detail::take_leaf_slots(w, bvh);
    if (bvh.nodes.empty()) {
        return w;
    }
    std::optional<SahCollapse<N>> sah;
    if (rule == WideCollapse::sah) {
        sah.emplace(bvh);
    }
    const auto kids_of = [&](std::uint32_t b) {
        Kids<N> kids;
        if (bvh.nodes[b].is_leaf()) {
            kids.add(bvh, b);  // only for the root: a wide root holding the single leaf
        } else {
            kids = sah ? sah->children(b) : greedy_children<N>(bvh, b);
        }
        order_kids(kids, order);
        return kids;
    };
    // The top levels serially, down to the wide depth with up to 64 nodes (N^depth; 16 for
    // BVH16), each subtree below them by its own task.
    constexpr std::uint32_t task_depth = N == 16 ? 1 : N == 8 ? 2 : 3;
    bvh_detail::convert_tree(
        w.nodes, WideNode<N>::empty(), task_depth,
        [&](const bvh_detail::ConvertItem& it, LargeVector<WideNode<N>>& out, const auto& push) {
            expand<N>(bvh, it, kids_of(it.source), out, push);
        },
        [](const WideNode<N>& in, const auto& map) {
            WideNode<N> n = in;
            for (unsigned i = 0; i < N; ++i) {
                if (n.occupied(i) && n.count[i] == 0) {
                    n.child[i] = map(n.child[i]);
                }
            }
            return n;
        });
    return w;
}

template WideBvh<4> collapse_bvh<4>(Bvh, ChildOrder, WideCollapse);
template WideBvh<8> collapse_bvh<8>(Bvh, ChildOrder, WideCollapse);
template WideBvh<16> collapse_bvh<16>(Bvh, ChildOrder, WideCollapse);

}  // namespace rtlab
