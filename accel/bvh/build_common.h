#pragma once
// Shared machinery of the BVH builders (internal to accel/bvh): which boxes are usable, the
// top-down recursion that emits Wald nodes in depth-first pair order (in parallel when asked), the
// object-median split and the depth guard that keeps every leaf at depth <= 64.

#include "accel/bvh/bvh.h"
#include "accel/task_tree.h"
#include "base/scratch_vector.h"
#include "base/thread_arena.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <tbb/parallel_for.h>
#include <utility>
#include <vector>

namespace rtlab::bvh_detail {

/// Empty when prim_ids references every usable primitive exactly once (ids < prim_count, none
/// twice, prim_count - unreferenced_count of them, padding_slot entries aside); else the first
/// violation. Shared by the validate() of every BVH layout.
std::string check_prim_ids(std::span<const std::uint32_t> prim_ids,
                           std::uint32_t prim_count,
                           std::uint32_t unreferenced_count);

/// Marks the slots of the leaf [first, first + count) in `used` (one flag per prim_ids slot);
/// empty, or the first violation: a range outside prim_ids, a slot already used, a padding slot.
std::string use_leaf_slots(std::span<const std::uint32_t> prim_ids,
                           std::vector<char>& used,
                           std::uint32_t first,
                           std::uint32_t count);

/// Empty when every slot that is no padding slot is in a leaf (`used`); else the violation.
std::string check_slots_covered(std::span<const std::uint32_t> prim_ids,
                                const std::vector<char>& used);

/// The info() walks: visit(node, depth, push) for every node reached depth first from node 0,
/// where push(child, depth) schedules a child (the last one pushed is visited next).
template <class F>
void walk_from_root(const F& visit) {
    struct Item {
        std::uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 0}};
    const auto push = [&](std::uint32_t node, std::uint32_t depth) {
        stack.push_back({node, depth});
    };
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        visit(it.node, it.depth, push);
    }
}

/// The sizes every BVH layout's info() reports: node count, bytes, bytes per input primitive and
/// references (prim_ids slots other than padding) per referenced primitive (1 unless spatial
/// splits put a primitive in several leaves).
AccelInfo size_info(std::size_t nodes,
                    std::size_t bytes,
                    std::uint32_t prim_count,
                    std::span<const std::uint32_t> prim_ids,
                    std::uint32_t unreferenced_count);

/// The SAH cost of the info() walks, sum(inner A * Ct) + sum(leaf A * n * Ci) over A(root) with
/// the build's Ct and Ci, with the leaf count and depth beside it. Terms are summed in the order
/// they are added, so layouts that walk the same tree alike report the same cost.
class SahTally {
public:
    SahTally(const Bvh::Config& cfg, const Bounds3f& root);
    /// An inner node (or inner child slot) of box b.
    void inner(const Bounds3f& b);
    /// A leaf of `count` primitives and box b at `depth`.
    void leaf(const Bounds3f& b, std::uint32_t count, std::uint32_t depth);
    /// Stores leaves, max_depth and sah_cost in i (Ci * prims when the root has no area).
    void finish(AccelInfo& i, std::size_t prims) const;

private:
    double ct_, ci_, root_area_;
    double cost_ = 0;
    std::uint64_t leaves_ = 0;
    std::uint32_t max_depth_ = 0;
};

/// The node bookkeeping of the validate() walks: every node reached once, none deeper than 64,
/// all of them reached.
class NodeWalk {
public:
    explicit NodeWalk(std::size_t nodes) : seen_(nodes, 0) {}
    /// Marks `node`, reached at `depth`; empty, or the violation (out of range, reached twice,
    /// depth > 64).
    std::string visit(std::uint32_t node, std::uint32_t depth);
    /// Empty when every node was visited; else how many were not.
    std::string unreached() const;

private:
    std::vector<char> seen_;
    std::size_t visited_ = 0;
};

/// Gives a layout converted from source tree b (PairBvh, WideBvh) b's leaf slots (moved: the
/// conversion reads only b's nodes), input counts and configuration.
template <class Layout>
void take_leaf_slots(Layout& out, Bvh& b) {
    out.prim_ids = std::move(b.prim_ids);
    out.prim_count = b.prim_count;
    out.unreferenced_count = b.unreferenced_count;
    out.config = b.config;
}

/// What Bvh's and WideBvh's validate() decide before walking nodes: check_prim_ids' violation, or
/// without nodes the verdict (valid when there are no primitives either); nullopt when the nodes
/// are to be walked.
std::optional<std::string> check_before_nodes(std::span<const std::uint32_t> prim_ids,
                                              std::uint32_t prim_count,
                                              std::uint32_t unreferenced_count,
                                              std::size_t nodes);

/// The validate() walks: for every Item (with members node and depth) reached depth first from
/// `root`, marks it in a NodeWalk of `nodes` nodes, then calls check(item, where, push), where
/// `where` ("node i: ") prefixes its violations and push(item) schedules a child (the last one
/// pushed is checked next). The first violation, else the nodes never reached (NodeWalk).
template <class Item, class F>
std::string check_from_root(std::size_t nodes, const Item& root, const F& check) {
    NodeWalk walk(nodes);
    std::vector<Item> stack{root};
    const auto push = [&](const Item& child) { stack.push_back(child); };
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const std::string where = "node " + std::to_string(it.node) + ": ";
        if (std::string e = walk.visit(it.node, it.depth); !e.empty()) {
            return where + e;
        }
        if (std::string e = check(it, where, push); !e.empty()) {
            return e;
        }
    }
    return walk.unreached();
}

/// Ranges at least this long are reduced (bounds, bins) in parallel blocks of `reduce_block`:
/// the top nodes of an unbalanced tree (a floor split off a mesh) would otherwise run one thread
/// for a whole level. Unions and counts are exact under any grouping: same trees for any threads.
inline constexpr std::uint32_t reduce_min = 1u << 16;
inline constexpr std::uint32_t reduce_block = 1u << 14;
/// Subtrees of at least this many primitives are built by tasks of their own (TaskTree).
inline constexpr std::uint32_t task_min = 4096;

/// The task tree of the BVH builders; leaf ids per chunk only for builders that list them so.
using BvhTaskTree = TaskTree<BvhNodes>;

/// TaskTree's relink of a BVH node: an inner node's child pair through node_of, a leaf's slots
/// through id_of (slots of one shared array, of builders without chunk lists, stay as they are).
inline constexpr auto relink_bvh_node = [](BvhNode n, const auto& node_of, const auto& id_of) {
    n.first =
        static_cast<std::uint32_t>(n.is_leaf() ? id_of(n.first, n.prim_count()) : node_of(n.first));
    return n;
};

/// f(k, lo, hi) for every block k = [lo, hi) of reduce_block indices of [0, n), in parallel.
template <class F>
void for_blocks(std::size_t n, const F& f) {
    const std::size_t blocks = (n + reduce_block - 1) / reduce_block;
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
        f(k, k * reduce_block, std::min<std::size_t>(n, (k + 1) * reduce_block));
    });
}

/// f(lo, hi) over [0, n): once for the whole of a range shorter than reduce_min, else for every
/// block of for_blocks, in parallel.
template <class F>
void for_range(std::size_t n, const F& f) {
    if (n < reduce_min) {
        f(std::size_t{0}, n);
    } else {
        for_blocks(n, [&](std::size_t, std::size_t lo, std::size_t hi) { f(lo, hi); });
    }
}

/// start[k] = how many i below block k's first index satisfy pred(i), for every block of
/// for_blocks and one past the last (the total): where block k's selected indices go when they
/// are packed in order. The same for any thread count.
template <class Pred>
std::vector<std::uint32_t> block_starts(std::size_t n, const Pred& pred) {
    std::vector<std::uint32_t> start((n + reduce_block - 1) / reduce_block + 1, 0);
    for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
        std::uint32_t count = 0;
        for (std::size_t i = lo; i < hi; ++i) {
            count += pred(i) ? 1u : 0u;
        }
        start[k + 1] = count;
    });
    for (std::size_t k = 1; k < start.size(); ++k) {
        start[k] += start[k - 1];
    }
    return start;
}

/// A node of another layout still to fill from node `source` of a source tree, at `depth`
/// below the root (see convert_tree).
struct ConvertItem {
    std::uint32_t source, target, depth;
};

/// Converts a tree into another node layout (bvh:pair, bvh4, bvh8) depth first from its root
/// (source node 0) into the empty `nodes`, the root's node (a copy of `blank`) at nodes[0]:
/// expand(item, out, push) fills out[item.target] from item.source, appends a node to `out` for
/// each inner child and push(ConvertItem) schedules it (the last pushed is expanded next). The
/// levels above `task_depth` run serially; each subtree below them is converted by its own task
/// into its own chunk (its root a copy of `blank` at chunk[0], inner child links as chunk indices),
/// then chunk k's node 0 fills its placeholder and its node j >= 1 lands at base[k] + j - 1 (chunks
/// appended in order), each node passed through relink(node, map) with map(j) that index. The
/// split depends on the tree only, so any thread count gives the same nodes.
template <class Nodes, class Expand, class Relink>
void convert_tree(Nodes& nodes,
                  const typename Nodes::value_type& blank,
                  std::uint32_t task_depth,
                  Expand&& expand,
                  Relink&& relink) {
    const auto run = [&](std::vector<ConvertItem> todo, Nodes& out,
                         std::vector<ConvertItem>* pending) {
        const auto push = [&](const ConvertItem& it) { todo.push_back(it); };
        while (!todo.empty()) {
            const ConvertItem it = todo.back();
            todo.pop_back();
            if (pending != nullptr && it.depth == task_depth) {
                pending->push_back(it);
            } else {
                expand(it, out, push);
            }
        }
    };
    std::vector<ConvertItem> pending;
    assert(nodes.empty());
    nodes.push_back(blank);
    run({{0, 0, 0}}, nodes, &pending);
    std::vector<Nodes> chunks(pending.size());
    tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t k) {
        chunks[k].push_back(blank);
        run({{pending[k].source, 0, 0}}, chunks[k], nullptr);
    });
    std::vector<std::size_t> base(pending.size() + 1, nodes.size());
    for (std::size_t k = 0; k < pending.size(); ++k) {
        base[k + 1] = base[k] + chunks[k].size() - 1;
    }
    nodes.resize(base.back());
    tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t k) {
        const auto map = [&](std::uint32_t j) {
            return static_cast<std::uint32_t>(base[k] + j - 1);
        };
        nodes[pending[k].target] = relink(chunks[k][0], map);
        for (std::size_t j = 1; j < chunks[k].size(); ++j) {
            nodes[base[k] + j - 1] = relink(chunks[k][j], map);
        }
    });
}

/// An unsigned integer that orders as its float does (f not NaN; -0 and +0 the same key): the
/// sign bit flipped for positives, every bit for negatives.
inline std::uint32_t float_order_key(float f) {
    const auto u = std::bit_cast<std::uint32_t>(f + 0.0f);  // -0 + 0 is +0
    return (u & 0x80000000u) != 0 ? ~u : u | 0x80000000u;
}

/// Stable radix sort of keys by their bits [32, 32 + bits) (a code above an id), on the fewest
/// digits of at most 11 bits: 65536 keys or more by the most significant digit (a parallel pass
/// in fixed blocks), then each bucket by the lower digits (LSD, buckets in parallel); fewer by LSD
/// passes. Keys made in id order and unique end in the order of sorting the whole keys, for any
/// thread count.
void radix_sort_by_high(ScratchVector<std::uint64_t>& keys, std::uint32_t bits);

/// Stably partitions v[b, e) by in_first(x) (those first, each part in its old order) through
/// scratch[b, e); returns the first slot of the second part. The stable order is unique, so the
/// result is the same for any thread count; ranges of reduce_min or more run in parallel blocks.
template <class Pred>
std::uint32_t stable_partition(std::span<std::uint32_t> v,
                               std::span<std::uint32_t> scratch,
                               std::uint32_t b,
                               std::uint32_t e,
                               const Pred& in_first) {
    if (e - b < reduce_min) {
        std::uint32_t l = b, r = b;
        for (std::uint32_t i = b; i < e; ++i) {
            if (in_first(v[i])) {
                v[l++] = v[i];
            } else {
                scratch[r++] = v[i];
            }
        }
        std::copy(scratch.begin() + b, scratch.begin() + r, v.begin() + l);
        return l;
    }
    const std::size_t n = e - b;
    const std::vector<std::uint32_t> start =
        block_starts(n, [&](std::size_t i) { return in_first(v[b + i]); });
    const std::uint32_t mid = b + start.back();
    for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
        std::size_t l = b + start[k], r = mid + (lo - start[k]);
        for (std::size_t i = b + lo; i < b + hi; ++i) {
            (in_first(v[i]) ? scratch[l++] : scratch[r++]) = v[i];
        }
    });
    for_range(n, [&](std::size_t lo, std::size_t hi) {
        std::copy(scratch.begin() + b + lo, scratch.begin() + b + hi, v.begin() + b + lo);
    });
    return mid;
}

/// ceil(log2(n)) for n >= 1 (0 for n = 1).
std::uint32_t ceil_log2(std::uint64_t n);

/// The configuration with every field clamped to its documented range.
Bvh::Config clamped(const Bvh::Config& cfg);

/// n primitives as the SAH counts them, in started blocks of cfg.sah_block: ceil(n / block), as
/// Embree's builders count them for leaves tested a SIMD block at a time (its sahBlockSize).
inline float sah_count(const Bvh::Config& cfg, std::uint32_t n) {
    // Blocks of one (the default) skip the integer division, which sweeps call twice per plane.
    const std::uint32_t b = cfg.sah_block;
    return static_cast<float>(b == 1 ? n : (n + b - 1) / b);
}

/// True when the SAH makes a range of n primitives a leaf whatever its splits: it fits one and
/// Ci * n <= Ct (n as sah_count counts it), so its leaf cost Ci * n * A is at most Ct * A, which no
/// split's Ct * A + Ci * (A_L n_L + A_R n_R) undercuts (for a finite area A; rounding is monotone,
/// so in floats too). The SAH builders make such ranges leaves without binning or sweeping them, as
/// Embree's builders make every range of up to minLeafSize primitives a leaf.
inline bool sah_leaf_anyway(const Bvh::Config& cfg, std::uint32_t n) {
    return n <= cfg.max_leaf_size &&
           cfg.intersection_cost * sah_count(cfg, n) <= cfg.traversal_cost;
}

/// The object bin of centroid coordinate c among `bins` bins from lo, scale = bins / extent:
/// floor((c - lo) * scale) clamped to [0, bins - 1]. c >= lo, so the product is >= 0 except for the
/// NaN of 0 * inf (c == lo with an extent so tiny that the scale overflowed): both mean bin 0; the
/// top edge (c == hi) and overflow clamp to the last bin, and the float is converted only in range.
inline std::uint32_t centroid_bin(float c, float lo, float scale, std::uint32_t bins) {
    const float f = (c - lo) * scale;
    if (!(f > 0.0f)) {
        return 0;
    }
    if (!(f < static_cast<float>(bins))) {
        return bins - 1;
    }
    return std::min(bins - 1, static_cast<std::uint32_t>(f));
}

/// A split of the id range [b, e): [b, mid) goes left, [mid, e) right (b < mid < e).
struct Split {
    std::uint32_t mid;   ///< first slot of the right child
    std::uint32_t axis;  ///< split axis stored in the node to order traversal
};

/// When TopDown::run computes a node's box: before its split, from its primitives, for splits
/// that read it (SAH costs); or after, as the union of its children's (its leaf range's for a
/// leaf), for splits that ignore it (LBVH, median): every primitive box is then read once, not
/// once per level. min and max are exact, so both give the same boxes.
enum class NodeBoxes { before_split, after_split };

/// State of one top-down build: input boxes, centres, the working order of usable primitive ids
/// (each node owns a contiguous range of it) and the output tree.
class TopDown {
public:
    /// Collects the usable primitives of `in` in id order; cfg must already be clamped.
    TopDown(const BuildInput& in, const Bvh::Config& cfg);

    std::span<const Bounds3f> boxes;  ///< input boxes by primitive id
    ScratchVector<float> centers;     ///< box centres by primitive id, x y z each (see center)
    std::vector<std::uint32_t> ids;   ///< usable primitive ids; node ranges index into it
    Bvh::Config config;               ///< clamped configuration

    /// The centre of primitive id's box.
    Vec3f center(std::uint32_t id) const {
        const float* c = &centers[3 * std::size_t{id}];
        return {c[0], c[1], c[2]};
    }
    /// Union of the boxes of ids[b, e).
    Bounds3f range_bounds(std::uint32_t b, std::uint32_t e) const;
    /// Union of the centres of ids[b, e).
    Bounds3f centroid_bounds(std::uint32_t b, std::uint32_t e) const;
    /// Object median of ids[b, e) on the largest centroid axis (ties by id); reorders the range.
    Split median_split(std::uint32_t b, std::uint32_t e);
    /// bvh:median's split function for run: a leaf once e - b fits in one, else median_split.
    static std::optional<Split> median_or_leaf(
        TopDown& t, std::uint32_t b, std::uint32_t e, const Bounds3f&, bool);
    /// True when a split of n primitives at `depth` must be balanced (children <= ceil(n/2)) so
    /// that every leaf below stays at depth <= 64: invariant depth + ceil_log2(n) <= 64.
    static bool must_balance(std::uint32_t depth, std::uint32_t n);

    /// Runs the recursion, children of task_min primitives or more as parallel TBB tasks when
    /// `parallel`; once. split(*this, b, e, box, balance) returns a Split or nullopt for a leaf;
    /// when balance is true it must return a balanced split, and it must split whenever e - b >
    /// max_leaf_size. It may run concurrently on disjoint ranges, touching only ids[b, e) and
    /// scratch of its own range or thread. With NodeBoxes::after_split the split is handed an empty
    /// box (it must not need one) and each node's box is filled in once its subtree is built.
    /// Returns the finished tree, the same for any thread count and either NodeBoxes.
    template <NodeBoxes Boxes = NodeBoxes::before_split, class SplitFn>
    Bvh run(SplitFn&& split, bool parallel = false) {
        Bvh bvh;
        bvh.prim_count = static_cast<std::uint32_t>(boxes.size());
        bvh.unreferenced_count = bvh.prim_count - static_cast<std::uint32_t>(ids.size());
        bvh.config = config;
        const auto n = static_cast<std::uint32_t>(ids.size());
        if (n != 0) {
            const Bounds3f root_box =
                Boxes == NodeBoxes::before_split ? range_bounds(0, n) : Bounds3f{};
            BvhTaskTree tree({task_min, parallel, 2}, n);
            build<Boxes>(tree, tree.root(), 0, split, 0, n, 0, root_box);
            tree.splice(bvh.nodes, nullptr, relink_bvh_node);
        }
        bvh.prim_ids = std::move(ids);  // the build is done with them
        return bvh;
    }

private:
    // The split of ids[b, e) at `depth`, or nullopt for a leaf.
    template <class SplitFn>
    std::optional<Split> decide(SplitFn& split,
                                std::uint32_t b,
                                std::uint32_t e,
                                std::uint32_t depth,
                                const Bounds3f& box) {
        const std::uint32_t n = e - b;
        std::optional<Split> s;
        if (n > 1) {
            s = split(*this, b, e, box, must_balance(depth, n));
            if (!s && n > config.max_leaf_size) {
                s = median_split(b, e);
            }
        }
        return s;
    }

    // The boxes of the children of ids[b, e) split at m: their ranges' unions (before_split), or
    // empty ones, filled in later (after_split).
    template <NodeBoxes Boxes>
    std::pair<Bounds3f, Bounds3f> child_boxes(std::uint32_t b,
                                              std::uint32_t m,
                                              std::uint32_t e) const {
        if constexpr (Boxes == NodeBoxes::before_split) {
            return {range_bounds(b, m), range_bounds(m, e)};
        } else {
            return {};
        }
    }

    // Writes the leaf of ids[b, e) to `out` and returns its box: the one handed down
    // (before_split) or its range's union (after_split).
    template <NodeBoxes Boxes>
    Bounds3f put_leaf(BvhNode& out, std::uint32_t b, std::uint32_t e, const Bounds3f& given) const {
        const Bounds3f box = Boxes == NodeBoxes::before_split ? given : range_bounds(b, e);
        out = BvhNode::make_leaf(box, b, e - b);
        return box;
    }
    // Writes an inner node with children from `first` to `out` and returns its box: the one handed
    // down (before_split) or the union of its built children's (after_split).
    template <NodeBoxes Boxes>
    static Bounds3f put_inner(BvhNode& out,
                              const Bounds3f& given,
                              Bounds3f left,
                              const Bounds3f& right,
                              std::uint32_t first,
                              std::uint32_t axis) {
        const Bounds3f box = Boxes == NodeBoxes::before_split ? given : left.extend(right);
        out = BvhNode::make_inner(box, first, axis);
        return box;
    }

    // Fills out.nodes[node] with the subtree of ids[b, e), appending its descendants in
    // depth-first pair order (both children, then the left subtree, then the right); returns the
    // node's box.
    template <NodeBoxes Boxes, class SplitFn>
    Bounds3f build(BvhTaskTree& tree,
                   BvhTaskTree::Chunk& out,
                   std::uint32_t node,
                   SplitFn& split,
                   std::uint32_t b,
                   std::uint32_t e,
                   std::uint32_t depth,
                   const Bounds3f& given) {
        const std::optional<Split> s = decide(split, b, e, depth, given);
        if (!s) {
            return put_leaf<Boxes>(out.nodes[node], b, e, given);
        }
        const auto left = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        out.nodes.emplace_back();
        if (tree.is_task(e - b)) {
            return build_forked<Boxes>(tree, out, split, {node, b, e, depth, left, *s, given});
        }
        // Neither child is a task: fork would build both inline; recurse directly (a lean frame).
        const auto [lg, rg] = child_boxes<Boxes>(b, s->mid, e);
        const Bounds3f lb = build<Boxes>(tree, out, left, split, b, s->mid, depth + 1, lg);
        const Bounds3f rb = build<Boxes>(tree, out, left + 1, split, s->mid, e, depth + 1, rg);
        return put_inner<Boxes>(out.nodes[node], given, lb, rb, left, s->axis);
    }

    // An inner node of build whose children may be tasks: out.nodes[node] over ids[b, e) at
    // `depth`, its box `given`, split by `split`, its children at left and left + 1.
    struct Forked {
        std::uint32_t node, b, e, depth, left;
        Split split;
        Bounds3f given;
    };

    // Builds f's children through TaskTree::fork and fills its node. Out of line, so that
    // build's own frame stays small (a deep recursion with the fork's branches in every frame
    // spilled out of L1 and slowed bvh:lbvh by a fifth).
    template <NodeBoxes Boxes, class SplitFn>
    [[gnu::noinline]] Bounds3f build_forked(BvhTaskTree& tree,
                                            BvhTaskTree::Chunk& out,
                                            SplitFn& split,
                                            const Forked& f) {
        const std::uint32_t b = f.b, m = f.split.mid, e = f.e, depth = f.depth, left = f.left;
        const auto [lg, rg] = child_boxes<Boxes>(b, m, e);
        Bounds3f lb, rb;
        tree.fork(
            out,
            TaskBranch{left, m - b,
                       [&, lg = lg](BvhTaskTree::Chunk& c, std::uint32_t at) {
                           lb = build<Boxes>(tree, c, at, split, b, m, depth + 1, lg);
                       }},
            TaskBranch{left + 1, e - m, [&, rg = rg](BvhTaskTree::Chunk& c, std::uint32_t at) {
                           rb = build<Boxes>(tree, c, at, split, m, e, depth + 1, rg);
                       }});
        return put_inner<Boxes>(out.nodes[f.node], f.given, lb, rb, left, f.split.axis);
    }
};

}  // namespace rtlab::bvh_detail
