// PairBvh: conversion from a Bvh, size figures and the invariant check.

#include "accel/bvh/pair_bvh.h"

#include "accel/bvh/build_common.h"

#include <utility>

namespace rtlab {

namespace {

/// Fills pair node nodes[it.target] from the children of inner node it.source of b, appending a
/// node for each inner child and pushing them so that child 0's subtree comes first: siblings'
/// nodes are adjacent (bvh_detail::convert_tree's expand).
template <class Push>
void expand(const Bvh& b,
            const bvh_detail::ConvertItem& it,
            LargeVector<PairNode>& nodes,
            const Push& push,
            ChildOrder order) {
    const BvhNode& src = b.nodes[it.source];
    // Child 0 the source's second child when that one's box is larger (ChildOrder::area).
    const bool flip = order == ChildOrder::area && b.nodes[src.first + 1].bounds().surface_area() >
                                                       b.nodes[src.first].bounds().surface_area();
    PairNode n{};
    bvh_detail::ConvertItem inner[2];
    int inner_count = 0;
    for (std::uint32_t c = 0; c < 2; ++c) {
        const std::uint32_t from = src.first + (flip ? 1 - c : c);
        const BvhNode& child = b.nodes[from];
        n.x[c] = child.lo.x;
        n.x[2 + c] = child.hi.x;
        n.y[c] = child.lo.y;
        n.y[2 + c] = child.hi.y;
        n.z[c] = child.lo.z;
        n.z[2 + c] = child.hi.z;
        if (child.is_leaf()) {
            n.child[c] = child.first;
            n.count[c] = child.prim_count();
        } else {
            n.child[c] = static_cast<std::uint32_t>(nodes.size());
            n.count[c] = 0;
            nodes.emplace_back();
            inner[inner_count++] = {from, n.child[c], it.depth + 1};
        }
    }
    n.count[0] |= src.axis() << 30;
    n.count[1] |= (flip ? 1u : 0u) << 30;
    nodes[it.target] = n;
    for (int k = inner_count - 1; k >= 0; --k) {
        push(inner[k]);
    }
}

}  // namespace

PairBvh PairBvh::convert(Bvh b, ChildOrder order) {
    PairBvh p;
    bvh_detail::take_leaf_slots(p, b);
    if (b.nodes.empty()) {
        return p;
    }
    const BvhNode& root = b.nodes[0];
    p.root_box = root.bounds();
    if (root.is_leaf()) {
        p.root_child = root.first;
        p.root_count = root.prim_count();
        return p;
    }
    // The top six levels serially (up to 64 subtrees below them), each subtree below them by
    // its own task.
    p.nodes.reserve(b.nodes.size() / 2);
    bvh_detail::convert_tree(
        p.nodes, PairNode{}, 6,
        [&](const bvh_detail::ConvertItem& it, LargeVector<PairNode>& out, const auto& push) {
            expand(b, it, out, push, order);
        },
        [](const PairNode& in, const auto& map) {
            PairNode n = in;
            for (int c = 0; c < 2; ++c) {
                if (n.count_of(c) == 0) {
                    n.child[c] = map(n.child[c]);
                }
            }
            return n;
        });
    return p;
}

AccelInfo PairBvh::info() const {
    AccelInfo i = bvh_detail::size_info(
        nodes.size(), nodes.size() * sizeof(PairNode) + prim_ids.size() * sizeof(std::uint32_t),
        prim_count, prim_ids, unreferenced_count);
    if (prim_ids.empty()) {
        return i;
    }
    // Computed here, not at conversion: a walk over the tree that a build need not wait for.
    bvh_detail::SahTally sah(config, root_box);
    if (root_count > 0) {
        sah.leaf(root_box, root_count, 0);
    } else {
        sah.inner(root_box);
        bvh_detail::walk_from_root([&](std::uint32_t node, std::uint32_t depth, const auto& push) {
            const PairNode& n = nodes[node];
            for (int c = 0; c < 2; ++c) {
                if (n.count_of(c) > 0) {
                    sah.leaf(n.child_bounds(c), n.count_of(c), depth + 1);
                } else {
                    sah.inner(n.child_bounds(c));
                    push(n.child[c], depth + 1);
                }
            }
        });
    }
    sah.finish(i, prim_ids.size());
    return i;
}

std::string PairBvh::validate() const {
    if (std::string e = bvh_detail::check_prim_ids(prim_ids, prim_count, unreferenced_count);
        !e.empty()) {
        return e;
    }
    if (prim_ids.empty()) {
        return nodes.empty() ? std::string{} : "nodes but no primitives";
    }
    std::vector<char> slot_used(prim_ids.size(), 0);
    const auto use_leaf = [&](std::uint32_t first, std::uint32_t count) -> std::string {
        if (count > config.max_leaf_size) {
            return "leaf of " + std::to_string(count) + " > max_leaf_size";
        }
        return bvh_detail::use_leaf_slots(prim_ids, slot_used, first, count);
    };
    if (root_count > 0) {
        if (!nodes.empty()) {
            return "a leaf root with inner nodes";
        }
        if (std::string e = use_leaf(root_child, root_count); !e.empty()) {
            return "root: " + e;
        }
    } else {
        // A pair node holds the children one level below it: its depth is theirs (1 for the
        // root's).
        struct Item {
            std::uint32_t node, depth;
            Bounds3f box;
        };
        const auto check = [&](const Item& it, const std::string& where,
                               auto& push) -> std::string {
            const PairNode& n = nodes[it.node];
            for (int c = 0; c < 2; ++c) {
                const Bounds3f box = n.child_bounds(c);
                if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z) ||
                    !it.box.contains(box)) {
                    return where + "child box empty, NaN or outside its parent";
                }
                if (n.count_of(c) > 0) {
                    if (std::string e = use_leaf(n.child[c], n.count_of(c)); !e.empty()) {
                        return where + e;
                    }
                } else {
                    push({n.child[c], it.depth + 1, box});
                }
            }
            return {};
        };
        if (std::string e = bvh_detail::check_from_root(nodes.size(), Item{0, 1, root_box}, check);
            !e.empty()) {
            return e;
        }
    }
    return bvh_detail::check_slots_covered(prim_ids, slot_used);
}

}  // namespace rtlab
