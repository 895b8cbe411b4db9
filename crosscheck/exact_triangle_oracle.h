#pragma once
// The exact oracle of the certified ray/triangle test (tests/exact_hit_test.cpp): CGAL's exact
// line/triangle intersection on the ray of exact_ray.h, brute force over a triangle list. It is
// compiled here, with this library's CGAL configuration, so that its callers see no CGAL type.

#include "intersect/hit.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace rtlab::xcheck {

/// The exact answer for one ray and one triangle.
struct ExactPairHit {
    bool hit = false;  ///< the ray meets the closed triangle at one point with t in [tmin, tmax]
    /// The float nearest to that point's exact t (ties to even; +-inf past the float range, as
    /// IEEE rounding gives); +inf on a miss.
    float t = std::numeric_limits<float>::infinity();
};

/// The exact answers for one ray against every triangle of a list.
struct ExactTriangleHits {
    std::vector<ExactPairHit> pairs;     ///< one per triangle, in list order
    std::uint32_t closest = invalid_id;  ///< the hit of smallest exact t; exact ties: the lowest id
};

/// Exact answers for `ray` against every triangle of `tris` (ids are indices), decided in CGAL's
/// exact kernel with the rules of intersect/triangle/exact_hit.h: the ray is {org + t dir : tmin
/// <= t <= tmax} with org, dir and the vertices as the exact reals the floats hold (an infinite
/// tmin or tmax leaves that side open; tmin = +inf or tmax = -inf is empty), the triangle is
/// closed, and a zero-area triangle or a line lying in the triangle's plane is a miss. The closest
/// hit is ordered by exact t, not by the rounded floats. Preconditions: finite vertices, a finite
/// origin, a non-zero finite direction, tmin and tmax not NaN. Cost: a few exact constructions
/// per triangle (the lazy kernel's interval filter decides most of them).
[[nodiscard]] ExactTriangleHits exact_triangle_hits(std::span<const Trianglef> tris,
                                                    const Rayf& ray);

}  // namespace rtlab::xcheck
