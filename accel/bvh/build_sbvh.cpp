// Spatial-split BVH (Stich, Friedrich & Dietrich 2009, "Spatial Splits in Bounding Volume
// Hierarchies"): binned SAH over references (a primitive's part inside a region, as a box), and
// where the best object split's children overlap by more than alpha of the root's area, also
// spatial splits: planes at bins of equal width over the node box, a straddling reference cut in
// two (each part clipped with the input's ClipFn when it has one, else its box cut at the plane).
// A primitive may then sit in several leaves (at most once in any one). O(N log N); subtrees of
// large ranges are tasks of the shared TaskTree (accel/task_tree.h), object and spatial bins and
// their sweep are the binning module's (accel/bvh/binning.h), and each node's allowance of
// extra references is split between its children by their sizes, so the tree is the same for any
// thread count.

#include "accel/bvh/binning.h"
#include "accel/bvh/build_common.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

/// The part of primitive `id` inside a region, bounded by `box`.
struct Ref {
    Bounds3f box;
    std::uint32_t id;
};

/// References in huge pages once large: the top nodes' arrays are rebuilt at every split, and
/// in 4 KiB pages the page faults cost a third of a two-thread build.
using Refs = LargeVector<Ref>;

/// Stich et al.'s alpha: spatial splits are tried where the object split's children overlap by
/// more than this fraction of the root's surface area.
constexpr float overlap_alpha = 1e-5f;
/// The references may number at most this many times the usable primitives.
constexpr double ref_budget = 2.0;
/// Subtrees of at least this many references are tasks of the TaskTree (more than the other
/// builders' bvh_detail::task_min: a spatial node's binning costs more per reference).
constexpr std::uint32_t sbvh_task_min = 1u << 14;

using Chunk = bvh_detail::BvhTaskTree::Chunk;

using Bins = binning::Bins<Bounds3f>;

/// The best split found so far of one kind (binning::BinSplit) with the spatial split's plane.
struct Candidate : binning::BinSplit<Bounds3f> {
    float plane = 0;
};

class SbvhBuilder {
public:
    // At least two bins: spatial splits need a plane between bins.
    SbvhBuilder(const BuildInput& in, const Bvh::Config& cfg)
        : in_(in), cfg_(cfg), bins_(std::max(cfg.bin_count, 2u)) {}

    Bvh run() {
        Bvh bvh;
        bvh.prim_count = static_cast<std::uint32_t>(in_.bounds.size());
        bvh.config = cfg_;
        Refs refs;
        Bounds3f root;
        for (std::uint32_t id = 0; id < bvh.prim_count; ++id) {
            if (is_usable_box(in_.bounds[id])) {
                refs.push_back({in_.bounds[id], id});
                root.extend(in_.bounds[id]);
            }
        }
        bvh.unreferenced_count = bvh.prim_count - static_cast<std::uint32_t>(refs.size());
        if (refs.empty()) {
            return bvh;
        }
        const auto budget =
            static_cast<std::size_t>((ref_budget - 1.0) * static_cast<double>(refs.size()));
        min_overlap_ = overlap_alpha * root.surface_area();
        bvh_detail::BvhTaskTree tree({sbvh_task_min, true, 0}, refs.size());
        build(tree, tree.root(), 0, std::move(refs), 0, root, budget);
        tree.splice(bvh.nodes, &bvh.prim_ids, bvh_detail::relink_bvh_node);
        return bvh;
    }

private:
    /// A box that binning::reduce_blocks can merge.
    struct Union : Bounds3f {
        void merge(const Union& o) { extend(o); }
    };

    static Bounds3f union_of(const Refs& refs) {
        Union u;
        binning::reduce_blocks(refs.size(), u, [&](Union& b, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                b.extend(refs[i].box);
            }
        });
        return u;
    }

    static Bounds3f centroid_bounds(const Refs& refs) {
        Union u;
        binning::reduce_blocks(refs.size(), u, [&](Union& b, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                b.extend(refs[i].box.center());
            }
        });
        return u;
    }

    float sah(std::uint32_t n) const { return bvh_detail::sah_count(cfg_, n); }

    /// Bounds of primitive r.id's part inside `region` (a box inside r.box): the clip function's
    /// polygon bounds grown by a few ulps of the primitive's coordinates (its vertices off the
    /// clip planes are rounded), or the region itself without one; empty when they miss.
    Bounds3f clip(const Ref& r, const Bounds3f& region) const {
        if (!in_.clip) {
            return region;
        }
        Bounds3f b = in_.clip(r.id, region);
        if (b.empty()) {
            return b;
        }
        const Bounds3f& whole = in_.bounds[r.id];
        for (unsigned a = 0; a < 3; ++a) {
            const float m = std::max(std::abs(whole.lo[a]), std::abs(whole.hi[a]));
            const float pad = m * (8.0f * std::numeric_limits<float>::epsilon());
            b.lo[a] -= pad;
            b.hi[a] += pad;
        }
        return intersection(b, region);
    }

    /// r's box with its `side` half (0: below the plane, 1: above) of axis a cut away.
    static Bounds3f half(const Bounds3f& box, std::uint32_t a, float plane, int side) {
        Bounds3f h = box;
        (side == 0 ? h.hi[a] : h.lo[a]) = plane;
        return h;
    }

    /// The SAH's best plane of axis a of g kept in best (binning::sweep with surface areas).
    void sweep(const Bins& g, std::uint32_t a, Candidate& best) const {
        binning::sweep(
            g, a, [](const Bounds3f& b) { return b.surface_area(); },
            [&](std::uint32_t n) { return sah(n); }, best);
    }

    /// The object bins' scale on each axis (0 where the centres coincide).
    std::array<float, 3> object_scale(const Bounds3f& cb) const {
        std::array<float, 3> scale{};
        for (std::uint32_t a = 0; a < 3; ++a) {
            const float extent = cb.hi[a] - cb.lo[a];
            scale[a] = extent > 0.0f ? static_cast<float>(bins_) / extent : 0.0f;
        }
        return scale;
    }

    /// Binned SAH over the references' centres (Wald 2007), with the children's boxes.
    Candidate object_split(const Refs& refs, const Bounds3f& cb) const {
        const std::array<float, 3> scale = object_scale(cb);
        Bins g(bins_, false);
        binning::reduce_blocks(refs.size(), g, [&](Bins& acc, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                const Vec3f c = refs[i].box.center();
                for (std::uint32_t a = 0; a < 3; ++a) {
                    const std::uint32_t k =
                        a * bins_ + bvh_detail::centroid_bin(c[a], cb.lo[a], scale[a], bins_);
                    acc.box[k].extend(refs[i].box);
                    ++acc.enter[k];
                }
            }
        });
        Candidate best;
        for (std::uint32_t a = 0; a < 3; ++a) {
            if (scale[a] != 0.0f) {
                sweep(g, a, best);
            }
        }
        return best;
    }

    /// True when axis a of the node box can hold spatial bins: a positive, finite extent.
    static bool spatial_axis(const Bounds3f& node, std::uint32_t a) {
        const float extent = node.hi[a] - node.lo[a];
        return extent > 0.0f && extent <= std::numeric_limits<float>::max();
    }

    /// Plane k of axis a's spatial bins over the node box (k = bins_: the box's top).
    float plane(const Bounds3f& node, std::uint32_t a, std::uint32_t k) const {
        if (k == bins_) {
            return node.hi[a];
        }
        const float w = (node.hi[a] - node.lo[a]) / static_cast<float>(bins_);
        return node.lo[a] + w * static_cast<float>(k);
    }

    /// The spatial bin holding coordinate x on axis a (by the planes above, so consistent).
    std::uint32_t spatial_bin(const Bounds3f& node, std::uint32_t a, float x) const {
        const float w = (node.hi[a] - node.lo[a]) / static_cast<float>(bins_);
        std::uint32_t k = 0;
        if (w > 0.0f) {
            const float f = (x - node.lo[a]) / w;
            k = f > 0.0f ? std::min(bins_ - 1, static_cast<std::uint32_t>(
                                                   std::min(f, static_cast<float>(bins_ - 1))))
                         : 0u;
        }
        // The float estimate may be off by one against the planes' own rounding.
        while (k > 0 && x < plane(node, a, k)) {
            --k;
        }
        while (k + 1 < bins_ && x >= plane(node, a, k + 1)) {
            ++k;
        }
        return k;
    }

    /// Adds reference r to the spatial bins of axis a: its parts in the bins it spans.
    void add_spatial(Bins& g, const Ref& r, const Bounds3f& node, std::uint32_t a) const {
        const std::uint32_t k0 = spatial_bin(node, a, r.box.lo[a]);
        const std::uint32_t k1 = spatial_bin(node, a, r.box.hi[a]);
        ++g.enter[a * bins_ + k0];
        ++g.leave[a * bins_ + k1];
        if (k0 == k1) {
            g.box[a * bins_ + k0].extend(r.box);
            return;
        }
        for (std::uint32_t k = k0; k <= k1; ++k) {
            Bounds3f slab = r.box;
            slab.lo[a] = std::max(slab.lo[a], plane(node, a, k));
            slab.hi[a] = std::min(slab.hi[a], plane(node, a, k + 1));
            g.box[a * bins_ + k].extend(clip(r, slab));
        }
    }

    /// Stich et al.'s spatial split: each reference's parts in the bins it spans (entering the
    /// first, leaving the last), the plane between bins with the lowest SAH.
    Candidate spatial_split(const Refs& refs, const Bounds3f& node) const {
        Bins g(bins_, true);
        binning::reduce_blocks(refs.size(), g, [&](Bins& acc, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                for (std::uint32_t a = 0; a < 3; ++a) {
                    if (spatial_axis(node, a)) {
                        add_spatial(acc, refs[i], node, a);
                    }
                }
            }
        });
        Candidate best;
        for (std::uint32_t a = 0; a < 3; ++a) {
            if (spatial_axis(node, a)) {
                sweep(g, a, best);
            }
        }
        best.plane = plane(node, best.axis, best.bin + 1);
        return best;
    }

    /// refs split into left and right (in refs' order, whatever the thread count) by
    /// place(r, left, right), which appends r or its parts to either or both; blocks of
    /// bvh_detail::reduce_block references in parallel for large ranges.
    template <class Place>
    static void partition(const Refs& refs, Refs& left, Refs& right, const Place& place) {
        const std::size_t n = refs.size();
        if (n < bvh_detail::reduce_min) {
            for (const Ref& r : refs) {
                place(r, left, right);
            }
            return;
        }
        std::vector<std::pair<Refs, Refs>> part((n + bvh_detail::reduce_block - 1) /
                                                bvh_detail::reduce_block);
        bvh_detail::for_blocks(n, [&](std::size_t k, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                place(refs[i], part[k].first, part[k].second);
            }
        });
        std::size_t nl = 0, nr = 0;
        for (const auto& [l, r] : part) {
            nl += l.size();
            nr += r.size();
        }
        left.reserve(nl);
        right.reserve(nr);
        for (const auto& [l, r] : part) {
            left.insert(left.end(), l.begin(), l.end());
            right.insert(right.end(), r.begin(), r.end());
        }
    }

    /// Moves refs into left/right by the object split c (centre bins as object_split made them).
    void partition_object(
        const Refs& refs, const Bounds3f& cb, const Candidate& c, Refs& left, Refs& right) const {
        const float scale = object_scale(cb)[c.axis];
        partition(refs, left, right, [&](const Ref& r, auto& l, auto& h) {
            const bool low = bvh_detail::centroid_bin(r.box.center()[c.axis], cb.lo[c.axis], scale,
                                                      bins_) <= c.bin;
            (low ? l : h).push_back(r);
        });
    }

    /// Moves refs into left/right by the plane of c: a reference on one side goes there, one
    /// straddling it is cut in two (a part that misses its side is dropped).
    void partition_spatial(const Refs& refs, const Candidate& c, Refs& left, Refs& right) const {
        const std::uint32_t a = c.axis;
        partition(refs, left, right, [&](const Ref& r, auto& l, auto& h) {
            if (r.box.hi[a] <= c.plane) {
                l.push_back(r);
            } else if (r.box.lo[a] >= c.plane) {
                h.push_back(r);
            } else {
                const Bounds3f lo = clip(r, half(r.box, a, c.plane, 0));
                const Bounds3f hi = clip(r, half(r.box, a, c.plane, 1));
                if (lo.empty() && hi.empty()) {
                    l.push_back(r);  // both parts rounded away: keep it whole
                    return;
                }
                if (!lo.empty()) {
                    l.push_back({lo, r.id});
                }
                if (!hi.empty()) {
                    h.push_back({hi, r.id});
                }
            }
        });
    }

    /// The object median of refs on the largest centroid axis (ties by id): balanced halves.
    static void median_partition(Refs& refs, Refs& left, Refs& right, std::uint32_t& axis) {
        axis = static_cast<std::uint32_t>(centroid_bounds(refs).largest_axis());
        const auto mid = refs.begin() + static_cast<std::ptrdiff_t>(refs.size() / 2);
        std::nth_element(refs.begin(), mid, refs.end(), [&](const Ref& x, const Ref& y) {
            const float cx = x.box.center()[axis], cy = y.box.center()[axis];
            return cx < cy || (cx == cy && x.id < y.id);
        });
        left.assign(refs.begin(), mid);
        right.assign(mid, refs.end());
    }

    static void make_leaf(Chunk& out, std::uint32_t node, const Refs& refs, const Bounds3f& box) {
        const auto first = static_cast<std::uint32_t>(out.ids.size());
        for (const Ref& r : refs) {
            out.ids.push_back(r.id);
        }
        out.nodes[node] = BvhNode::make_leaf(box, first, static_cast<std::uint32_t>(refs.size()));
    }

    /// A node's two children (refs split into left and right, the node's split axis), or false
    /// for a leaf. Spatial splits are tried where the object split's children overlap enough, and
    /// taken when cheaper and within `budget`, which they reduce by the references they add.
    bool split(Refs& refs,
               const Bounds3f& box,
               std::uint32_t depth,
               std::size_t& budget,
               Refs& left,
               Refs& right,
               std::uint32_t& axis) const {
        const auto n = static_cast<std::uint32_t>(refs.size());
        if (bvh_detail::TopDown::must_balance(depth, n)) {
            if (n <= cfg_.max_leaf_size) {
                return false;
            }
            median_partition(refs, left, right, axis);
            return true;
        }
        constexpr float none = std::numeric_limits<float>::infinity();
        const Bounds3f cb = centroid_bounds(refs);
        const Candidate obj = object_split(refs, cb);
        Candidate sp;
        if (budget > 0 && obj.cost < none &&
            intersection(obj.left, obj.right).surface_area() > min_overlap_) {
            sp = spatial_split(refs, box);
        }
        const float area = box.surface_area();
        if (n <= cfg_.max_leaf_size &&
            cfg_.intersection_cost * sah(n) * area <=
                cfg_.traversal_cost * area + cfg_.intersection_cost * std::min(obj.cost, sp.cost)) {
            return false;
        }
        if (sp.cost < obj.cost) {
            partition_spatial(refs, sp, left, right);
            axis = sp.axis;
            const std::size_t extra = left.size() + right.size() - n;
            if (!left.empty() && !right.empty() && left.size() < n && right.size() < n &&
                extra <= budget) {
                budget -= extra;
                return true;
            }
            left.clear();
            right.clear();
        }
        if (obj.cost < none) {
            partition_object(refs, cb, obj, left, right);
            axis = obj.axis;
            if (!left.empty() && !right.empty()) {
                return true;
            }
            left.clear();
            right.clear();
        }
        if (n <= cfg_.max_leaf_size) {
            return false;
        }
        median_partition(refs, left, right, axis);
        return true;
    }

    // Fills out.nodes[node] with the subtree of refs (box: their union), appending its
    // descendants in depth-first pair order; it may add up to `budget` references.
    void build(bvh_detail::BvhTaskTree& tree,
               Chunk& out,
               std::uint32_t node,
               Refs refs,
               std::uint32_t depth,
               const Bounds3f& box,
               std::size_t budget) const {
        const auto n = static_cast<std::uint32_t>(refs.size());
        Refs left, right;
        std::uint32_t axis = 0;
        if (n == 1 || bvh_detail::sah_leaf_anyway(cfg_, n) ||
            !split(refs, box, depth, budget, left, right, axis)) {
            make_leaf(out, node, refs, box);
            return;
        }
        refs = {};
        // The remaining allowance, shared by the children's sizes.
        const auto left_budget = static_cast<std::size_t>(
            static_cast<double>(budget) * static_cast<double>(left.size()) /
            static_cast<double>(left.size() + right.size()));
        const std::size_t right_budget = budget - left_budget;
        const Bounds3f left_box = union_of(left), right_box = union_of(right);
        const auto pair = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        out.nodes.emplace_back();
        out.nodes[node] = BvhNode::make_inner(box, pair, axis);
        const std::size_t nl = left.size(), nr = right.size();
        tree.fork(
            out,
            TaskBranch{pair, nl,
                       [&](Chunk& c, std::uint32_t at) {
                           build(tree, c, at, std::move(left), depth + 1, left_box, left_budget);
                       }},
            TaskBranch{pair + 1, nr, [&](Chunk& c, std::uint32_t at) {
                           build(tree, c, at, std::move(right), depth + 1, right_box, right_budget);
                       }});
    }

    const BuildInput& in_;
    Bvh::Config cfg_;
    std::uint32_t bins_;
    float min_overlap_ = 0;
};

}  // namespace

Bvh build_bvh_sbvh(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads) {
    return with_threads(threads, [&] { return SbvhBuilder(in, bvh_detail::clamped(cfg)).run(); });
}

}  // namespace rtlab
