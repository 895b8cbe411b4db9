#pragma once
// The one query API every acceleration structure offers. A structure never sees primitives: it
// is built from their bounds, and traversal calls the caller's leaf callback with the caller's
// primitive id. Counting compiles away unless a TraversalStats is passed.

#include "intersect/bounds.h"
#include "intersect/ray.h"

#include <cmath>
#include <concepts>
#include <cstdint>
#include <functional>
#include <limits>
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
/// loop) and test a leaf at once; whether it does is the caller's choice (a tracer's option).
/// prim_ids may hold padding_slot entries between leaves.
template <class A>
concept LeafRangeAccel = requires(const A& a, Rayf& ray, const Rayf& cray) {
    { a.prim_ids[0] } -> std::convertible_to<std::uint32_t>;
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

/// An interval [lo, hi] of dot(dir, x) over the points x of a primitive.
struct SlabExtent {
    float lo, hi;
};

/// Build-time only: the extent along `dir` of primitive `id`, holding every point a float test
/// of it may report (outward_extent). Layouts that bound primitives by slabs other than the
/// box's (the wide BVHs' `bounds=dop14`) use it; without it they take the extent of the box.
using ExtentFn = std::function<SlabExtent(std::uint32_t id, const Vec3f& dir)>;

/// dot(dir, p) in double, summed x, y, z: exact terms when dir's components are +-1 or 0.
inline double extent_dot(const Vec3f& dir, const Vec3f& p) {
    return static_cast<double>(dir.x) * static_cast<double>(p.x) +
           static_cast<double>(dir.y) * static_cast<double>(p.y) +
           static_cast<double>(dir.z) * static_cast<double>(p.z);
}

/// The extent [lo, hi] computed in double from float data by a few sums and products per term
/// (error below 4 * 2^-53 * mag, mag the sum of the terms' magnitudes), widened by 2^-22 * mag
/// (a few float ulps, as sphere boxes get one: the float tests of a primitive may report points a
/// rounding outside its exact shape), then rounded outward to floats.
inline SlabExtent outward_extent(double lo, double hi, double mag) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    const double pad = std::ldexp(mag, -22);
    const double l = lo - pad, h = hi + pad;
    const auto fl = static_cast<float>(l), fh = static_cast<float>(h);
    return {static_cast<double>(fl) <= l ? fl : std::nextafter(fl, -inf),
            static_cast<double>(fh) >= h ? fh : std::nextafter(fh, inf)};
}

/// What a builder receives: one box per primitive (index = primitive id), and optional exact
/// geometry queries: the part inside a box, the extent along a direction.
struct BuildInput {
    std::span<const Bounds3f> bounds;  ///< primitive bounds; must outlive the build call only
    ClipFn clip;                       ///< optional exact clipping for perfect splits
    ExtentFn extent = {};              ///< optional exact extents along a direction
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
