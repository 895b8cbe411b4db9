// Parallel binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies",
// with the parallel scheme of its section 4 and of Embree's builders): each node bins all three
// axes in one pass over 32-byte primitive references (box + id, moved by the partition, so no id
// indirection), takes the children's boxes from the bins and their centroid bounds from the
// partition. A node of n primitives uses min(bins, 4 + n/20) bins per axis (Embree's BinMapping
// rule): small nodes, the most numerous, reset and sweep few bins. Nodes of at least
// `reduce_min` primitives bin data-parallel in fixed blocks and partition into the other of two
// buffers (ping-pong; offsets from each block's bins, so one pass); subtrees of at least
// `task_min` primitives are tasks of the shared TaskTree (accel/task_tree.h). The bins, sweep and
// in-place partition are the binning module's (accel/bvh/binning.h) over SSE boxes, half areas.
// Deterministic: every decision depends on the node's primitives only (box unions and counts are
// exact under any grouping, the block partition is stable), so any thread count gives the same
// tree. Cost: O(N log N) work, O(N) memory besides the tree.

#include "accel/bvh/binned_refs.h"
#include "accel/bvh/binning.h"
#include "accel/bvh/build_common.h"
#include "base/scratch_vector.h"
#include "base/thread_arena.h"

#include <algorithm>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <vector>

namespace rtlab {

namespace {

using binned::Box;
using Bins = binning::Bins<Box>;
using binned::PrimRef;
using binned::V4;

// Subtrees of bvh_detail::task_min primitives or more are tasks; nodes of reduce_min or more bin
// and partition in parallel blocks of reduce_block (fixed, so the work split never depends on the
// threads).
using bvh_detail::reduce_min;
using bvh_detail::task_min;
constexpr std::size_t block = bvh_detail::reduce_block;

/// A node's primitive range with its box and the bounds of its doubled centroids.
struct Range {
    std::uint32_t b = 0, e = 0;
    bool alt = false;  ///< its references are in the builder's scratch_, else in refs_
    Box box;
    Box cent;  ///< bounds of lo + hi over the range
    std::uint32_t size() const { return e - b; }
    /// Block k of the fixed blocks the parallel passes cut the range into.
    std::pair<std::uint32_t, std::uint32_t> block_span(std::size_t k) const {
        return {static_cast<std::uint32_t>(b + k * block),
                static_cast<std::uint32_t>(std::min<std::size_t>(e, b + (k + 1) * block))};
    }
    std::size_t blocks() const { return (size() + block - 1) / block; }
};

class Builder {
public:
    Builder(const BuildInput& in, const Bvh::Config& cfg) : config_(cfg), boxes_(in.bounds) {}

    Bvh run() {
        Bvh bvh;
        bvh.prim_count = static_cast<std::uint32_t>(boxes_.size());
        bvh.config = config_;
        Range root = collect();
        bvh.unreferenced_count = bvh.prim_count - root.size();
        if (root.size() == 0) {
            return bvh;
        }
        // Chunk after chunk: the node order this builder has always had.
        bvh_detail::BvhTaskTree tree({task_min, true, 2, TaskLayout::chunks}, root.size());
        subtree(tree, tree.root(), 0, root, 0);
        tree.splice(bvh.nodes, nullptr, bvh_detail::relink_bvh_node);
        bvh.prim_ids.resize(refs_.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, refs_.size(), block),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                  bvh.prim_ids[i] = refs_[i].id;
                              }
                          });
        return bvh;
    }

private:
    /// The split of a range, or none for a leaf.
    struct Decision {
        bool leaf = true;
        std::uint32_t axis = 0;
        Range left, right;
    };

    Bvh::Config config_;
    std::span<const Bounds3f> boxes_;
    LargeScratchVector<PrimRef> refs_;     // filled by collect()'s blocks
    LargeScratchVector<PrimRef> scratch_;  // partition buffer for the parallel passes

    /// The usable primitives as references, in id order, with the root box and centroid bounds.
    Range collect() {
        const std::size_t n = boxes_.size();
        const std::size_t blocks = (n + block - 1) / block;
        std::vector<std::uint32_t> offset(blocks + 1, 0);
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
            std::uint32_t c = 0;
            for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i) {
                c += is_usable_box(boxes_[i]) ? 1 : 0;
            }
            offset[k + 1] = c;
        });
        for (std::size_t k = 0; k < blocks; ++k) {
            offset[k + 1] += offset[k];
        }
        refs_.resize(offset[blocks]);
        if (refs_.size() >= reduce_min) {
            scratch_.resize(refs_.size());
        }
        std::vector<Range> part(blocks);
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
            std::uint32_t out = offset[k];
            Range& r = part[k];
            for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i) {
                const Bounds3f& bb = boxes_[i];
                if (is_usable_box(bb)) {
                    PrimRef& p = refs_[out++];
                    p = {{bb.lo.x, bb.lo.y, bb.lo.z},
                         static_cast<std::uint32_t>(i),
                         {bb.hi.x, bb.hi.y, bb.hi.z},
                         0};
                    r.box.extend(p);
                    r.cent.extend(p.twice_center());
                }
            }
        });
        Range root;
        root.e = static_cast<std::uint32_t>(refs_.size());
        for (const Range& r : part) {
            root.box.extend(r.box);
            root.cent.extend(r.cent);
        }
        return root;
    }

    /// Builds the subtree of r into out.nodes[slot] and below; big children become tasks.
    void subtree(bvh_detail::BvhTaskTree& tree,
                 bvh_detail::BvhTaskTree::Chunk& out,
                 std::uint32_t slot,
                 const Range& r,
                 std::uint32_t depth) {
        const Decision d = decide(r, depth);
        if (d.leaf) {
            if (r.alt) {
                std::copy(scratch_.begin() + r.b, scratch_.begin() + r.e, refs_.begin() + r.b);
            }
            out.nodes[slot] = BvhNode::make_leaf(r.box.bounds(), r.b, r.size());
            return;
        }
        const auto left = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        out.nodes.emplace_back();
        out.nodes[slot] = BvhNode::make_inner(r.box.bounds(), left, d.axis);
        const auto child = [&](const Range& c) {
            return [&](bvh_detail::BvhTaskTree::Chunk& ch, std::uint32_t at) {
                subtree(tree, ch, at, c, depth + 1);
            };
        };
        tree.fork(out, TaskBranch{left, d.left.size(), child(d.left)},
                  TaskBranch{left + 1, d.right.size(), child(d.right)});
    }

    /// Leaf or split for range r at `depth`: SAH over the bins, else the object median when the
    /// range is too big for a leaf or the depth guard asks for balance.
    Decision decide(const Range& r, std::uint32_t depth) {
        Decision d;
        const std::uint32_t n = r.size();
        if (n <= 1) {
            return d;
        }
        const bool balance = bvh_detail::TopDown::must_balance(depth, n);
        if (!balance && bvh_detail::sah_leaf_anyway(config_, n)) {
            return d;
        }
        const std::uint32_t nb = std::min(config_.bin_count, 4 + n / 20);
        float cl[4], ch[4];
        r.cent.lo.store(cl);
        r.cent.hi.store(ch);
        const bool spread = ch[0] > cl[0] || ch[1] > cl[1] || ch[2] > cl[2];
        if (!balance && nb >= 2 && spread) {
            float scale[3];
            for (int a = 0; a < 3; ++a) {
                const float extent = ch[a] - cl[a];
                scale[a] = extent > 0.0f ? static_cast<float>(nb) / extent : 0.0f;
            }
            // Small nodes reuse this thread's bins: nothing between binning and partitioning
            // them can run another task on this thread. Big nodes bin in parallel (their
            // thread may run other tasks while it waits), so they own their bins, and keep each
            // block's bins for the partition's offsets.
            thread_local Bins small;
            Bins big;
            std::vector<Bins> per_block;
            Bins& bins = r.size() < reduce_min ? small : big;
            bin(r, nb, V4::set(cl[0], cl[1], cl[2]), V4::set(scale[0], scale[1], scale[2]), bins,
                per_block);
            binning::BinSplit<Box> best;
            for (std::uint32_t a = 0; a < 3; ++a) {
                if (ch[a] > cl[a]) {
                    binning::sweep(
                        bins, a, [](const Box& x) { return x.half_area_filled(); },
                        [&](std::uint32_t c) { return bvh_detail::sah_count(config_, c); }, best);
                }
            }
            if (best.cost < std::numeric_limits<float>::infinity()) {
                const float area = r.box.half_area();
                const float leaf_cost =
                    config_.intersection_cost * bvh_detail::sah_count(config_, n) * area;
                const float split_cost =
                    config_.traversal_cost * area + config_.intersection_cost * best.cost;
                if (n <= config_.max_leaf_size && leaf_cost <= split_cost) {
                    return d;
                }
                d.leaf = false;
                d.axis = best.axis;
                partition(r, bins, per_block, best, cl[best.axis], scale[best.axis], d);
                return d;
            }
        }
        if (n <= config_.max_leaf_size && !balance) {
            return d;
        }
        median(r, d);
        return d;
    }

    /// The buffer holding r's references.
    PrimRef* refs_of(const Range& r) { return r.alt ? scratch_.data() : refs_.data(); }
    const PrimRef* refs_of(const Range& r) const { return r.alt ? scratch_.data() : refs_.data(); }

    /// All three axes binned over r into out; a big r bins its blocks in parallel into
    /// per_block, merged into out in block order.
    void bin(const Range& r,
             std::uint32_t nb,
             V4 lo,
             V4 scale,
             Bins& out,
             std::vector<Bins>& per_block) const {
        const PrimRef* refs = refs_of(r);
        out.reset(nb, false);
        binning::reduce_blocks(
            r.size(), out,
            [&](Bins& acc, std::size_t first, std::size_t end) {
                const float top = static_cast<float>(nb - 1);
                alignas(16) int k[4];
                for (std::size_t i = r.b + first; i < r.b + end; ++i) {
                    const PrimRef& p = refs[i];
                    ((p.twice_center() - lo) * scale).bins(top, k);
                    for (std::uint32_t a = 0; a < 3; ++a) {
                        const std::size_t s = a * nb + static_cast<std::uint32_t>(k[a]);
                        acc.box[s].extend(p);
                        ++acc.enter[s];
                    }
                }
            },
            &per_block);
    }

    /// Moves the references of bins [0, best.bin] on best.axis to the front of r: in place for a
    /// small r, into the other buffer for a big one; fills d's children (boxes from the sweep,
    /// centroid bounds from the pass).
    void partition(const Range& r,
                   const Bins& bins,
                   const std::vector<Bins>& per_block,
                   const binning::BinSplit<Box>& best,
                   float lo,
                   float scale,
                   Decision& d) {
        const std::uint32_t axis = best.axis, split = best.bin;
        d.left.box = best.left;
        d.right.box = best.right;
        // The bin of V4::bins is <= split, without its clamps and conversion: the bin is trunc
        // of f = (c - lo) * scale clamped to [0, nb - 1] (NaN -> 0), and split < nb - 1, so it
        // is <= split exactly when f < split + 1 or f is NaN.
        const float limit = static_cast<float>(split + 1);
        const auto goes_left = [&](const PrimRef& p) {
            return !((p.lo[axis] + p.hi[axis] - lo) * scale >= limit);
        };
        const std::uint32_t mid = r.b + bins.left_of(axis, split);
        if (r.size() < reduce_min) {
            PrimRef* refs = refs_of(r);
            binning::partition(refs + r.b, refs + r.e, goes_left, [&](const PrimRef& p, bool left) {
                (left ? d.left : d.right).cent.extend(p.twice_center());
            });
            d.left.alt = d.right.alt = r.alt;
        } else {
            parallel_partition(r, per_block, axis, split, goes_left, mid, d);
        }
        d.left.b = r.b;
        d.left.e = mid;
        d.right.b = mid;
        d.right.e = r.e;
    }

    /// Stable partition of a big range into the other buffer (ping-pong: no copy back): each
    /// block's offsets from its own bins' counts, one scatter pass. Every
    /// step is exact whatever the threads, so the order is deterministic.
    template <class Pred>
    void parallel_partition(const Range& r,
                            const std::vector<Bins>& per_block,
                            std::uint32_t axis,
                            std::uint32_t split,
                            const Pred& goes_left,
                            std::uint32_t mid,
                            Decision& d) {
        const std::size_t blocks = per_block.size();
        std::vector<std::uint32_t> lefts(blocks + 1, 0), rights(blocks + 1, 0);
        for (std::size_t k = 0; k < blocks; ++k) {
            const auto [b, e] = r.block_span(k);
            const std::uint32_t c = per_block[k].left_of(axis, split);
            lefts[k + 1] = lefts[k] + c;
            rights[k + 1] = rights[k] + (e - b - c);
        }
        const PrimRef* src = refs_of(r);
        PrimRef* dst = r.alt ? refs_.data() : scratch_.data();
        std::vector<Box> lc(blocks), rc(blocks);
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
            const auto [b, e] = r.block_span(k);
            std::size_t l = r.b + lefts[k], rr = mid + rights[k];
            for (std::size_t i = b; i < e; ++i) {
                const PrimRef& p = src[i];
                if (goes_left(p)) {
                    dst[l++] = p;
                    lc[k].extend(p.twice_center());
                } else {
                    dst[rr++] = p;
                    rc[k].extend(p.twice_center());
                }
            }
        });
        for (std::size_t k = 0; k < blocks; ++k) {
            d.left.cent.extend(lc[k]);
            d.right.cent.extend(rc[k]);
        }
        d.left.alt = d.right.alt = !r.alt;
    }

    /// Object median of r on its largest centroid axis (ties by id), children measured by a pass.
    void median(const Range& r, Decision& d) {
        const std::uint32_t axis = static_cast<std::uint32_t>(r.cent.bounds().largest_axis());
        const std::uint32_t mid = r.b + r.size() / 2;
        PrimRef* refs = refs_of(r);
        std::nth_element(refs + r.b, refs + mid, refs + r.e,
                         [axis](const PrimRef& x, const PrimRef& y) {
                             const float cx = x.lo[axis] + x.hi[axis];
                             const float cy = y.lo[axis] + y.hi[axis];
                             return cx < cy || (cx == cy && x.id < y.id);
                         });
        d.leaf = false;
        d.axis = axis;
        d.left.b = r.b;
        d.left.e = mid;
        d.right.b = mid;
        d.right.e = r.e;
        for (Range* c : {&d.left, &d.right}) {
            c->alt = r.alt;
            for (std::uint32_t i = c->b; i < c->e; ++i) {
                c->box.extend(refs[i]);
                c->cent.extend(refs[i].twice_center());
            }
        }
    }
};

}  // namespace

/// Parallel binned SAH on `threads` TBB threads (0: TBB's default); the tree does not depend on
/// the thread count.
Bvh build_bvh_binned_parallel(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    Builder b(in, bvh_detail::clamped(cfg));
    return with_threads(threads, [&] { return b.run(); });
}

}  // namespace rtlab
