#pragma once
// The one query API every acceleration structure offers. A structure never sees primitives: it
// is built from their bounds, and traversal calls the caller's leaf callback with the caller's
// primitive id. Counting compiles away unless a TraversalStats is passed.

#include "intersect/bounds.h"
#include "intersect/ray.h"

#include <concepts>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

namespace rtlab {

/// Machine-independent traversal counters (summed over the rays traced with it).
struct TraversalStats {
    std::uint64_t rays = 0;   ///< rays started
    std::uint64_t nodes = 0;  ///< inner and leaf nodes (kd, BVH) or cells (grid) visited
    std::uint64_t prims = 0;  ///< leaf callbacks, i.e. ray-primitive tests

    void count_ray() { ++rays; }
    void count_node() { ++nodes; }
    void count_prim() { ++prims; }
    void count_prims(std::uint32_t n) { prims += n; }
    TraversalStats& operator+=(const TraversalStats& o) {
        rays += o.rays;
        nodes += o.nodes;
        prims += o.prims;
        return *this;
    }
};

/// The default: no counting; every call compiles to nothing.
struct NoStats {
    void count_ray() {}
    void count_node() {}
    void count_prim() {}
    void count_prims(std::uint32_t) {}
};

/// Either NoStats or TraversalStats (passed by reference to traversal).
template <class S>
concept StatsSink = requires(S& s) {
    s.count_ray();
    s.count_node();
    s.count_prim();
    s.count_prims(std::uint32_t{});
};

/// Closest-hit leaf callback: tests primitive `id`; on a hit inside [ray.tmin, ray.tmax] it records
/// the hit, shrinks ray.tmax to the hit's t and returns true.
template <class F>
concept ClosestHitFn = requires(F& f, std::uint32_t id, Rayf& ray) {
    { f(id, ray) } -> std::convertible_to<bool>;
};

/// Any-hit leaf callback: returns true when primitive `id` blocks the ray's window; the first
/// true ends traversal.
template <class F>
concept AnyHitFn = requires(F& f, std::uint32_t id, const Rayf& ray) {
    { f(id, ray) } -> std::convertible_to<bool>;
};

/// Leaf-range callback: tests the primitives of leaf slots [first, first + count) (see
/// LeafRangeAccel) against ray (R is Rayf for closest hit, which shrinks ray.tmax, const Rayf for
/// any hit) and returns true on a hit.
template <class F, class R>
concept LeafRangeFn = requires(F& f, std::uint32_t first, std::uint32_t count, R& ray) {
    { f(first, count, ray) } -> std::convertible_to<bool>;
};

namespace detail {
/// A leaf-range callback that never hits, used to state LeafRangeAccel.
struct NullLeafRange {
    bool operator()(std::uint32_t, std::uint32_t, const Rayf&) const { return false; }
};
}  // namespace detail

/// The prim_ids entry of a padding slot: a structure may pad prim_ids so that its leaves start at
/// aligned slots (whole SIMD groups of slot-ordered leaf data); a padding slot lies in no leaf.
inline constexpr std::uint32_t padding_slot = 0xffffffffu;

/// Optional: a structure whose leaves are ranges of `prim_ids` slots can hand a caller whole
/// leaves, so the caller may store its primitive data in slot order (no id indirection in the hot
/// loop) and test a leaf at once. `soa_leaves` says whether callers should. prim_ids may hold
/// padding_slot entries between leaves.
template <class A>
concept LeafRangeAccel = requires(const A& a, Rayf& ray, const Rayf& cray) {
    { a.prim_ids[0] } -> std::convertible_to<std::uint32_t>;
    { a.soa_leaves } -> std::convertible_to<bool>;
    { a.intersect_leaves(ray, detail::NullLeafRange{}) } -> std::same_as<bool>;
    { a.occluded_leaves(cray, detail::NullLeafRange{}) } -> std::same_as<bool>;
};

/// The one rule every builder applies: a primitive box is indexed only when its coordinates are
/// finite and lo <= hi on every axis. An empty box is hit by no ray, a NaN box bounds no real
/// geometry, and an infinite one would make every enclosing node infinite (unbounded primitives
/// such as planes belong outside the structures). Such primitives are never offered to a leaf
/// callback, by any structure.
inline bool is_usable_box(const Bounds3f& b) {
    return is_finite(b.lo) && is_finite(b.hi) && b.lo.x <= b.hi.x && b.lo.y <= b.hi.y &&
           b.lo.z <= b.hi.z;
}

/// Build-time only: the part of primitive `id` inside `box`, as a (possibly empty) box. Gives
/// kd-trees "perfect splits" (Havran; Wald & Havran 2006); without it they use the clipped
/// bounds.
using ClipFn = std::function<Bounds3f(std::uint32_t id, const Bounds3f& box)>;

/// The diagonal directions of the structures' extra slabs: (1, 1, 1), (1, 1, -1), (1, -1, 1) and
/// (-1, 1, 1), unnormalised (with the box's three axes, the 14-DOP's seven slab directions;
/// Kay & Kajiya 1986, Klosowski et al. 1998).
inline constexpr float diag_dirs[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};

/// dot(diag_dirs[k], p) in double: each term exact (+-p's component), the two sums rounded (error
/// below 2 * 2^-53 times |p.x| + |p.y| + |p.z|).
inline double diag_dot(unsigned k, const Vec3f& p) {
    return static_cast<double>(diag_dirs[k][0]) * static_cast<double>(p.x) +
           static_cast<double>(diag_dirs[k][1]) * static_cast<double>(p.y) +
           static_cast<double>(diag_dirs[k][2]) * static_cast<double>(p.z);
}

/// The corner of box b lowest along diag_dirs[k] (`low`) or highest.
inline Vec3f diag_corner(const Bounds3f& b, unsigned k, bool low) {
    const auto pick = [&](unsigned a) { return (diag_dirs[k][a] > 0) == low ? b.lo[a] : b.hi[a]; };
    return {pick(0), pick(1), pick(2)};
}

/// A primitive's extents along diag_dirs: every point x of it has lo[k] <= dot(diag_dirs[k], x)
/// <= hi[k] (exactly: the values are rounded outward).
struct DiagExtents {
    float lo[4];
    float hi[4];
};

/// Build-time only: the DiagExtents of primitive `id`. Without it, structures that use them take
/// the extents of the primitive's box, which add nothing to the box.
using DiagFn = std::function<DiagExtents(std::uint32_t id)>;

/// DiagExtents of a box (its corners'), rounded outward.
DiagExtents diag_extents_of_box(const Bounds3f& b);

/// DiagExtents from bounds lo[k] <= dot(diag_dirs[k], x) <= hi[k] computed in double from float
/// data by a few sums and products per term (error below 4 * 2^-53 * mag[k], mag[k] the sum of
/// the terms' magnitudes): widened by 2^-22 * mag[k] (a few float ulps, as sphere boxes get one:
/// the float tests of a primitive may report points a rounding outside its exact shape), then
/// rounded outward to floats.
DiagExtents diag_extents_rounded(const double lo[4], const double hi[4], const double mag[4]);

/// What a builder receives: one box per primitive (index = primitive id), an optional clip and
/// optional diagonal extents.
struct BuildInput {
    std::span<const Bounds3f> bounds;  ///< primitive bounds; must outlive the build call only
    ClipFn clip;                       ///< optional exact clipping for perfect splits
    DiagFn diag = {};                  ///< optional extents along diag_dirs (wide `bounds=dop14`)
};

/// Size and quality figures of a built structure, for reports.
struct AccelInfo {
    std::uint64_t nodes = 0;      ///< all nodes (grid: cells)
    std::uint64_t leaves = 0;     ///< leaves (grid: non-empty cells)
    std::uint32_t max_depth = 0;  ///< deepest leaf (root = 0; grid: 0)
    std::uint64_t bytes = 0;      ///< memory of nodes, index lists and cells
    double bytes_per_prim = 0;    ///< bytes / primitive count
    double sah_cost = 0;          ///< the structure's own cost-model value (documented per kind)
    double refs_per_prim = 0;     ///< primitive references / primitive count (BVH: 1)
};

namespace detail {
/// Leaf callbacks that never hit, used to state the Accel concept.
struct NullClosestHit {
    bool operator()(std::uint32_t, Rayf&) const { return false; }
};
struct NullAnyHit {
    bool operator()(std::uint32_t, const Rayf&) const { return false; }
};
}  // namespace detail

/// What every structure offers, and everything the tracer relies on: closest-hit and any-hit
/// queries with and without counting, each for both values of the IsRobust template parameter
/// (conservative box tests, Ize 2013), plus bounds, figures and the invariant check. Structures
/// are built by free builder functions listed in the registry (accel/registry.cpp), so building is
/// not part of the concept. `validate()` returns an empty string when every invariant holds, else
/// a description of the first violation.
template <class A>
concept Accel = requires(const A& a,
                         Rayf& ray,
                         const Rayf& cray,
                         TraversalStats& st,
                         detail::NullClosestHit closest,
                         detail::NullAnyHit any) {
    { a.intersect(ray, closest) } -> std::same_as<bool>;
    { a.template intersect<false>(ray, closest, st) } -> std::same_as<bool>;
    { a.template intersect<true>(ray, closest, st) } -> std::same_as<bool>;
    { a.template intersect<true>(ray, closest) } -> std::same_as<bool>;
    { a.occluded(cray, any) } -> std::same_as<bool>;
    { a.template occluded<false>(cray, any, st) } -> std::same_as<bool>;
    { a.template occluded<true>(cray, any, st) } -> std::same_as<bool>;
    { a.template occluded<true>(cray, any) } -> std::same_as<bool>;
    { a.bounds() } -> std::same_as<Bounds3f>;
    { a.info() } -> std::same_as<AccelInfo>;
    { a.validate() } -> std::same_as<std::string>;
};

}  // namespace rtlab
