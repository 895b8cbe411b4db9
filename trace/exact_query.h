#pragma once
// Certified closest and any hits of rays against triangles (the `exact` query mode): a
// structure's robust traversal (conservative box tests, Ize 2013) offers every triangle the exact
// ray may touch, the certified predicate (intersect/triangle/exact_hit.h) tests each, and the
// closest hit is the one of smallest exact t, exact ties going to the lowest primitive id. The
// traversal's window ends one float past the best hit's rounded t, so no triangle whose exact t
// ties or beats it is culled. The answer is a function of the triangles and rays alone: the same
// for every structure, thread count and SIMD level.

#include "accel/accel.h"
#include "accel/any_accel.h"
#include "intersect/hit.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace rtlab {

/// How often the exact query needed exact arithmetic.
struct ExactCounts {
    std::uint64_t rays = 0;           ///< rays traced
    std::uint64_t tests = 0;          ///< certified ray/triangle tests
    std::uint64_t fallbacks = 0;      ///< tests and t comparisons decided in exact arithmetic
    std::uint64_t fallback_rays = 0;  ///< rays with at least one fallback

    ExactCounts& operator+=(const ExactCounts& o) {
        rays += o.rays;
        tests += o.tests;
        fallbacks += o.fallbacks;
        fallback_rays += o.fallback_rays;
        return *this;
    }
};

/// The triangles of an exact query: tris[i] is primitive i of the structure, ids[i] its global id
/// (the id hits report and ties are broken by). For a structure that hands out whole leaves
/// (LeafRangeAccel), slot_tris/slot_ids may hold them in its leaf-slot order (exact_slots), and
/// leaves are then tested from there, without an id indirection.
struct ExactTriangles {
    std::span<const Trianglef> tris;
    std::span<const std::uint32_t> ids;
    std::span<const Trianglef> slot_tris;
    std::span<const std::uint32_t> slot_ids;
};

/// Triangles and global ids in the leaf-slot order of structure a (empty vectors unless it hands
/// out whole leaves); padding slots repeat the first slot's.
std::pair<std::vector<Trianglef>, std::vector<std::uint32_t>> exact_slots(
    const AnyAccel& a, std::span<const Trianglef> tris, std::span<const std::uint32_t> ids);

/// Certified closest hit of every ray against q through structure a: hits[i] is rays[i]'s (a miss
/// keeps prim == invalid_id, t = +inf). Rays with a non-finite origin or direction, or a NaN window
/// end, miss; a ray with a denormal direction component, which slab tests cannot see (its
/// reciprocal overflows), is tested against every triangle. Adds traversal counts to *stats and
/// fallback counts to *counts when given; rays in parallel (TBB).
void exact_closest(const AnyAccel& a,
                   const ExactTriangles& q,
                   std::span<const Rayf> rays,
                   std::span<Hit> hits,
                   TraversalStats* stats = nullptr,
                   ExactCounts* counts = nullptr);

/// Certified any hit: blocker[i] is the global id of a triangle that rays[i]'s window exactly
/// meets (whichever traversal met first), or invalid_id.
void exact_any(const AnyAccel& a,
               const ExactTriangles& q,
               std::span<const Rayf> rays,
               std::span<std::uint32_t> blocker,
               TraversalStats* stats = nullptr,
               ExactCounts* counts = nullptr);

}  // namespace rtlab
