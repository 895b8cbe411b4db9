#pragma once
// Havran's recursive ray traversal TA^B_rec (V. Havran, "Heuristic Ray Shooting Algorithms", PhD
// thesis, Czech Technical University, 2000, appendix C): the stack holds entry and exit *points*
// (position and signed distance t) instead of t-intervals, so each inner node is classified by
// comparing the coordinates of the current entry and exit points with the split (the N and P
// cases) and a distance is computed only when the ray crosses the plane inside the node. Unlike
// Havran's Z cases, a point exactly on the split visits both children (a primitive lying in the
// plane may be referenced by one side only).
// Internal to accel/kdtree/kdtree.h: the caller has clipped the ray to the scene box and routes
// rays with a zero (or denormal) direction component, the only ones that can lie in a split
// plane, to the t-value walk, which visits both children of such a plane.

#include "accel/kdtree/node.h"
#include "intersect/box/slabs.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace rtlab::kd_detail {

/// A point of the ray on the TA^B_rec stack: its signed distance t, its position p, the node
/// whose cell starts there (the far child of the split that made it; none for the ray's exit
/// from the scene box) and the stack index of the exit point that was current when it was pushed.
struct HavranPoint {
    static constexpr std::uint32_t none = 0xFFFFFFFFu;
    float t;
    float p[3];
    std::uint32_t node;
    std::uint32_t prev;
};

/// Robust mode: a computed point's coordinate b lies within this of the exact ray point it stands
/// for. Its t is a computed crossing (split - org) * inv_dir, within gamma(3) relative of the exact
/// one, or another point's t when clamped (then within that point's bound of the exact crossing:
/// see havran_walk), and never a lowered t; the coordinate adds the rounding of a multiplication
/// and an addition, so gamma(3) |dir t| + gamma(2) (|org| + |dir t|) <= gamma(6) (|org| + |dir t|).
/// The absolute term covers results in the subnormal range, where each operation may err by
/// half of denorm_min.
inline float havran_pad(const Rayf& ray, std::uint32_t b, float t) {
    return (std::abs(ray.org[b]) + std::abs(ray.dir[b] * t)) * gamma_bound<float>(6) +
           4.0f * std::numeric_limits<float>::denorm_min();
}

/// Robust mode: a t lowered below every exact distance it may stand for (gamma(3) relative, as
/// the t-value walk widens its split distances), for the stop test only.
inline float havran_lowered(float t) {
    const float pad = std::abs(t) * (2.0f * gamma_bound<float>(3));
    return std::isfinite(pad) ? t - pad : t;
}

/// Fills the point at distance t; axis `on` (< 3) lies exactly in a split plane at `split`.
inline void havran_set_point(
    HavranPoint& pt, const Rayf& ray, float t, std::uint32_t on, float split) {
    pt.t = t;
    for (std::uint32_t b = 0; b < 3; ++b) {
        pt.p[b] = b == on ? split : ray.org[b] + ray.dir[b] * t;
    }
}

/// The TA^B_rec walk over [t_enter, t_exit] (the ray's window clipped to the scene box): leaf(
/// offset, count) is called for every leaf the window meets, front to back, and returns true to
/// stop. After a leaf, the walk goes on only while the next cell's entry distance is at most
/// ray.tmax (shrunk by closest hits), so a hit beyond the current leaf never ends it early. Robust
/// mode treats a coordinate within havran_pad of the split as on both sides and lowers the next
/// cell's entry distance by 2 gamma(3) for the stop test, as the t-value walk does. Returns
/// whether leaf stopped the walk.
///
/// Why robust mode is conservative (every leaf whose cell the exact ray meets in its window is
/// visited): (1) the root points lie on the exact ray at t_enter <= the exact entry and t_exit >=
/// the exact exit (clip_slabs<true>), so the computed segment covers the exact one; (2) a pushed
/// point's t is the computed crossing, within gamma(3) of the exact one, clamped into the current
/// points' [t_en, t_ex]: a clamp only moves it to an end of a segment that already covers the
/// exact one, and its axis coordinate is the split, the child cell's own boundary; t is never
/// lowered, so the bounds do not compound down the tree; (3) hence every coordinate is within
/// havran_pad of the exact ray's point it stands for, so "both endpoints below the plane (by more
/// than the pad)" implies the exact segment is below it (a segment lies between its endpoints);
/// (4) the stop test compares a lowered entry with tmax, so a cell whose exact entry precedes the
/// closest hit found is still visited. Rays with a zero or subnormal direction component never
/// get here (they take the t-value walk), so inv_dir is finite and t never NaN.
///
/// A pushed point keeps the computed t: its coordinates, the pads and later clamps need a t within
/// gamma(3) of the exact crossing. Lowering it at the push (for the stop test) made nested splits
/// through one vertex clamp to ever lower t, until a point's coordinates fell a few ulps short of
/// the plane the exact ray reaches there and a child was skipped.
template <bool IsRobust, std::uint32_t DepthLimit, class S, class Leaf>
bool havran_walk(const KdNode* nodes,
                 const Rayf& ray,
                 const SlabRay<float>& sr,
                 float t_enter,
                 float t_exit,
                 S& stats,
                 Leaf& leaf) {
    // Pushes along a root-to-leaf path (at most DepthLimit) above the first two slots, plus the
    // one slot a push may skip (the current entry point).
    HavranPoint stack[DepthLimit + 3];
    std::uint32_t en = 0, ex = 1;
    havran_set_point(stack[en], ray, t_enter, 3, 0.0f);
    havran_set_point(stack[ex], ray, t_exit, 3, 0.0f);
    stack[ex].node = HavranPoint::none;
    std::uint32_t index = 0;
    for (;;) {
        for (;;) {
            const KdNode& n = nodes[index];
            stats.count_node();
            if (n.is_leaf()) {
                break;
            }
            const std::uint32_t a = n.axis();
            const float split = n.split();
            const std::uint32_t below = index + 1, above = n.above_child();
            const float pe = stack[en].p[a], px = stack[ex].p[a];
            // A point on the plane touches both children: a primitive lying in the plane may be
            // referenced by either side only (Havran's Z cases would skip the other), so a child
            // is visited when either point is on its side or on the plane. Robust mode widens
            // the plane by each point's rounding bound.
            float pad_e = 0.0f, pad_x = 0.0f;
            if constexpr (IsRobust) {
                pad_e = havran_pad(ray, a, stack[en].t);
                pad_x = havran_pad(ray, a, stack[ex].t);
            }
            const bool go_below = pe <= split + pad_e || px <= split + pad_x;
            const bool go_above = pe >= split - pad_e || px >= split - pad_x;
            if (!go_above || !go_below) {
                index = go_below ? below : above;  // the N and P cases
                continue;
            }
            const std::uint32_t near_child = sr.neg[a] ? above : below;
            const std::uint32_t far_child = sr.neg[a] ? below : above;
            // The crossing of the split plane becomes the near child's exit point and the far
            // child's entry point (Havran: push it, skipping the slot of the current entry).
            float t = (split - sr.org[a]) * sr.inv_dir[a];
            t = t < stack[en].t ? stack[en].t : (t > stack[ex].t ? stack[ex].t : t);
            const std::uint32_t prev = ex;
            if (++ex == en) {
                ++ex;
            }
            havran_set_point(stack[ex], ray, t, a, split);  // the computed t: see above
            stack[ex].node = far_child;
            stack[ex].prev = prev;
            index = near_child;
        }
        const KdNode& n = nodes[index];
        if (leaf(n.prim_offset(), n.prim_count())) {
            return true;
        }
        // The current exit point is the next cell's entry: go on while it is not beyond tmax
        // (robust: while its lowered t is not, so a hit in the next cell is never cut off).
        if (stack[ex].node == HavranPoint::none) {
            return false;
        }
        if constexpr (IsRobust) {
            if (havran_lowered(stack[ex].t) > ray.tmax) {
                return false;
            }
        } else if (stack[ex].t > ray.tmax) {
            return false;
        }
        en = ex;
        index = stack[en].node;
        ex = stack[en].prev;
    }
}

}  // namespace rtlab::kd_detail
