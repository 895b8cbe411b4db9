#pragma once
// The deterministic parallel task tree of the top-down builders (the task splitting of Embree's
// generic builder, with chunks spliced as madmann91/bvh's mini-tree builder stitches its trees):
// a child subtree of at least task_min primitives is built by a TBB task into a chunk of its own
// (nodes and leaf id lists, links local to the chunk), and one splice at the end lays the chunks
// out in the order a serial build gives. The tree is the same for any thread count and threshold.
// (TaskLayout::chunks instead keeps each chunk's nodes together: the same for any thread count.)

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <utility>
#include <vector>

namespace rtlab {

/// Where TaskTree::splice puts the chunks' nodes and ids.
enum class TaskLayout {
    serial,  ///< where a serial build puts them: each subtree's nodes after its root's pair
    chunks,  ///< each chunk's together, the chunks breadth first (bvh:pbinned's layout)
};

/// How a TaskTree splits the work and lays it out.
struct TaskSettings {
    std::uint32_t task_min = 4096;  ///< child subtrees of at least this many primitives are tasks
    bool parallel = true;           ///< false: every subtree is built inline into the root chunk
    std::uint32_t nodes_per_prim = 0;  ///< nodes reserved per primitive of a new chunk (0: none)
    TaskLayout layout = TaskLayout::serial;  ///< where splice puts the chunks
};

/// One child of a TaskTree::fork: build(chunk, slot) fills the child's subtree, its root at
/// chunk.nodes[slot]; `slot` is a node the parent already added, or TaskTree's `append` for a
/// root added where the child's nodes start (pre-order layouts); `size` counts its primitives.
template <class F>
struct TaskBranch {
    std::uint32_t slot;
    std::size_t size;
    F build;
};

/// The recursion of one build over node container Nodes (BvhNodes, the kd-tree's nodes) and leaf
/// id container Ids, for builders whose leaves list ids per chunk (others leave them empty).
template <class Nodes, class Ids = std::vector<std::uint32_t>>
class TaskTree {
public:
    /// A subtree's share of the output: nodes[0] is its root, links and leaf offsets are local.
    struct Chunk {
        Nodes nodes;
        Ids ids;

    private:
        friend class TaskTree;
        // A child built into a chunk of its own: its root goes to nodes[slot]; its other nodes
        // and its ids go where this chunk's nodes reached `at` and its ids `ids_at`.
        struct Sub {
            std::uint32_t slot;
            std::size_t at, ids_at;
            std::unique_ptr<Chunk> chunk;
        };
        std::vector<Sub> subs;
        std::size_t nodes_below = 0, ids_below = 0;  // nodes past node 0 and ids, subs included
    };

    /// The slot of a child whose root the tree adds where its nodes start.
    static constexpr std::uint32_t append = std::numeric_limits<std::uint32_t>::max();

    /// A tree whose root chunk holds the root node (a default Node) for a build of `prims`.
    TaskTree(const TaskSettings& settings, std::size_t prims) : settings_(settings) {
        start(root_, prims);
    }

    /// The chunk of the root: the recursion starts at its node 0.
    Chunk& root() { return root_; }

    /// Builds both children of a node of `out`: in order inline, or, when parallel, a child of at
    /// least task_min primitives as a task into a new chunk concurrently with the other. Returns
    /// the children's root slots in `out` (the one given, or the one added for `append`).
    template <class L, class R>
    std::pair<std::uint32_t, std::uint32_t> fork(Chunk& out,
                                                 TaskBranch<L> left,
                                                 TaskBranch<R> right) {
        const bool lt = is_task(left.size), rt = is_task(right.size);
        if (!lt && !rt) {
            const std::uint32_t l = inline_child(out, left);
            return {l, inline_child(out, right)};
        }
        return fork_tasks(out, left, right, lt, rt);
    }

    /// True when a child of `size` primitives becomes a task of its own (a parallel build and
    /// size >= task_min). Below that a builder may recurse directly, as fork would inline it.
    bool is_task(std::size_t size) const {
        return settings_.parallel && size >= settings_.task_min;
    }

    /// Lays every chunk out into `nodes` (and `ids` when not null) by the settings' layout: each
    /// node and id where the serial build writes it, or chunk after chunk. relink(node, node_of,
    /// id_of) returns the node with each link j mapped to node_of(j) and a leaf's local list offset
    /// o of `count` ids to id_of(o, count). Chunks are copied in parallel; a tree of one chunk is
    /// moved.
    template <class Relink>
    void splice(Nodes& nodes, Ids* ids, const Relink& relink) {
        if (root_.subs.empty()) {
            nodes = std::move(root_.nodes);
            if (ids != nullptr) {
                *ids = std::move(root_.ids);
            }
            return;
        }
        count(root_);
        std::vector<Place> places;
        if (settings_.layout == TaskLayout::serial) {
            place(root_, 0, 1, 0, places);
        } else {
            place_chunks(places);
        }
        nodes.resize(1 + root_.nodes_below);
        if (ids != nullptr) {
            ids->resize(root_.ids_below);
        }
        tbb::parallel_for(std::size_t{0}, places.size(),
                          [&](std::size_t p) { copy(places[p], nodes, ids, relink); });
    }

private:
    // fork with at least one child a task: that child into a new chunk, concurrently with the
    // other. Out of line, so that the recursion that calls fork keeps a small stack frame (the
    // TBB task objects are 64-byte aligned and large; inlined into a recursive builder they made
    // every level's frame 1.2 KB, and a deep recursion then ran out of L1).
    template <class L, class R>
    [[gnu::noinline]] std::pair<std::uint32_t, std::uint32_t> fork_tasks(
        Chunk& out, TaskBranch<L>& left, TaskBranch<R>& right, bool lt, bool rt) {
        std::unique_ptr<Chunk> lc = lt ? new_chunk(left.size) : nullptr;
        std::unique_ptr<Chunk> rc = rt ? new_chunk(right.size) : nullptr;
        std::uint32_t l_slot = lt ? place_holder(out, left.slot) : left.slot;
        std::uint32_t r_slot = right.slot;
        const std::size_t at = out.nodes.size(), ids_at = out.ids.size();
        tbb::parallel_invoke(
            [&] {
                if (lt) {
                    left.build(*lc, 0);
                } else {
                    l_slot = inline_child(out, left);
                }
            },
            [&] {
                if (rt) {
                    right.build(*rc, 0);
                } else {
                    r_slot = inline_child(out, right);
                }
            });
        if (lt) {
            out.subs.push_back({l_slot, at, ids_at, std::move(lc)});
        }
        if (rt) {
            r_slot = place_holder(out, r_slot);
            out.subs.push_back({r_slot, out.nodes.size(), out.ids.size(), std::move(rc)});
        }
        return {l_slot, r_slot};
    }

    // Where a chunk lands: its node 0 at `root`, its other nodes from `start`, its ids from
    // `id_start` (children's nodes and ids interleaved as place() computes).
    struct Place {
        const Chunk* chunk;
        std::size_t root, start, id_start;
        bool interleave;  // TaskLayout::serial: the subs' nodes and ids amid the chunk's
    };

    void start(Chunk& c, std::size_t prims) const {
        if (settings_.nodes_per_prim != 0) {
            const std::size_t cap =
                settings_.parallel ? std::min<std::size_t>(prims, 2 * settings_.task_min) : prims;
            c.nodes.reserve(settings_.nodes_per_prim * cap);
        }
        c.nodes.emplace_back();
    }

    std::unique_ptr<Chunk> new_chunk(std::size_t prims) const {
        auto c = std::make_unique<Chunk>();
        start(*c, prims);
        return c;
    }

    // The slot of a child's root in `out`: `slot`, or a node added now for `append`.
    static std::uint32_t place_holder(Chunk& out, std::uint32_t slot) {
        if (slot != append) {
            return slot;
        }
        out.nodes.emplace_back();
        return static_cast<std::uint32_t>(out.nodes.size() - 1);
    }

    template <class F>
    static std::uint32_t inline_child(Chunk& out, TaskBranch<F>& child) {
        const std::uint32_t slot = place_holder(out, child.slot);
        child.build(out, slot);
        return slot;
    }

    // Sets nodes_below and ids_below of c and every chunk under it.
    static void count(Chunk& c) {
        c.nodes_below = c.nodes.size() - 1;
        c.ids_below = c.ids.size();
        for (typename Chunk::Sub& s : c.subs) {
            count(*s.chunk);
            c.nodes_below += s.chunk->nodes_below;
            c.ids_below += s.chunk->ids_below;
        }
    }

    // Global index of c's local node j >= 1: past the nodes of the subs added before it.
    static std::size_t node_at(const Place& p, std::size_t j) {
        std::size_t shift = 0;
        for (const typename Chunk::Sub& s : p.chunk->subs) {
            if (!p.interleave || s.at > j) {
                break;
            }
            shift += s.chunk->nodes_below;
        }
        return p.start + j - 1 + shift;
    }

    // Appends where c and the chunks under it land, c first.
    static void place(const Chunk& c,
                      std::size_t root,
                      std::size_t start,
                      std::size_t id_start,
                      std::vector<Place>& out) {
        const Place p{&c, root, start, id_start, true};
        out.push_back(p);
        std::size_t node_shift = 0, id_shift = 0;
        for (const typename Chunk::Sub& s : c.subs) {
            place(*s.chunk, node_at(p, s.slot), start + s.at - 1 + node_shift,
                  id_start + s.ids_at + id_shift, out);
            node_shift += s.chunk->nodes_below;
            id_shift += s.chunk->ids_below;
        }
    }

    // Appends where every chunk lands in TaskLayout::chunks: breadth first, each chunk's nodes
    // past node 0 and its ids after the previous chunk's.
    void place_chunks(std::vector<Place>& out) const {
        out.push_back({&root_, 0, 1, 0, false});
        std::size_t next = root_.nodes.size(), next_id = root_.ids.size();
        for (std::size_t i = 0; i < out.size(); ++i) {
            const Place p = out[i];
            for (const typename Chunk::Sub& s : p.chunk->subs) {
                out.push_back({s.chunk.get(), node_at(p, s.slot), next, next_id, false});
                next += s.chunk->nodes.size() - 1;
                next_id += s.chunk->ids.size();
            }
        }
    }

    // Copies one chunk's nodes (but the subs' slots, which their chunks fill) and ids.
    template <class Relink>
    static void copy(const Place& p, Nodes& nodes, Ids* ids, const Relink& relink) {
        const Chunk& c = *p.chunk;
        if (c.subs.empty()) {
            copy_whole(p, nodes, ids, relink);  // most chunks, holding most nodes
            return;
        }
        const auto node_of = [&](std::uint32_t j) { return node_at(p, j); };
        std::size_t k = 0, node_shift = 0;
        for (std::size_t j = 0; j < c.nodes.size(); ++j) {
            for (; p.interleave && k < c.subs.size() && c.subs[k].at <= j; ++k) {
                node_shift += c.subs[k].chunk->nodes_below;
            }
            const bool holder = std::any_of(c.subs.begin(), c.subs.end(),
                                            [&](const auto& s) { return s.slot == j; });
            if (j != 0 && holder) {
                continue;
            }
            // A leaf's ids follow a sub's when they start past the sub's, or at it and the leaf
            // has ids (so it was filled after the sub was forked) or comes after it (pre-order).
            const auto id_of = [&](std::size_t o, std::size_t count) {
                std::size_t shift = 0;
                for (const typename Chunk::Sub& s : c.subs) {
                    if (p.interleave &&
                        (s.ids_at < o || (s.ids_at == o && (count != 0 || s.at <= j)))) {
                        shift += s.chunk->ids_below;
                    }
                }
                return p.id_start + o + shift;
            };
            const std::size_t at = j == 0 ? p.root : p.start + j - 1 + node_shift;
            nodes[at] = relink(c.nodes[j], node_of, id_of);
        }
        if (ids == nullptr) {
            return;
        }
        k = 0;
        std::size_t id_shift = 0;
        for (std::size_t j = 0; j < c.ids.size(); ++j) {
            for (; p.interleave && k < c.subs.size() && c.subs[k].ids_at <= j; ++k) {
                id_shift += c.subs[k].chunk->ids_below;
            }
            (*ids)[p.id_start + id_shift + j] = c.ids[j];
        }
    }

    // copy for a chunk without subs: its node j >= 1 lands at start + j - 1, its id o at
    // id_start + o.
    template <class Relink>
    static void copy_whole(const Place& p, Nodes& nodes, Ids* ids, const Relink& relink) {
        const Chunk& c = *p.chunk;
        const auto node_of = [&](std::uint32_t j) { return p.start + j - 1; };
        const auto id_of = [&](std::size_t o, std::size_t) { return p.id_start + o; };
        nodes[p.root] = relink(c.nodes[0], node_of, id_of);
        for (std::size_t j = 1; j < c.nodes.size(); ++j) {
            nodes[p.start + j - 1] = relink(c.nodes[j], node_of, id_of);
        }
        if (ids != nullptr) {
            std::copy(c.ids.begin(), c.ids.end(), ids->begin() + p.id_start);
        }
    }

    TaskSettings settings_;
    Chunk root_;
};

}  // namespace rtlab
