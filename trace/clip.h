#pragma once
// Exact-ish clipping of a triangle to a box (Sutherland & Hodgman 1974, polygon clipping against
// the six slab planes), for kd-tree perfect splits (Havran 2000; Wald & Havran 2006). The result
// is the bounds of the clipped polygon, intersected with the box to absorb rounding. And the
// extents of triangles and spheres along a direction (ExtentFn), for the wide BVHs'
// `bounds=dop14`.

#include "accel/accel.h"
#include "intersect/bounds.h"
#include "intersect/sphere/sphere.h"
#include "intersect/triangle/triangle.h"
#include "intersect/vec.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rtlab {

/// Bounds of the part of triangle (a, b, c) inside box, rounded outward: they contain the exact
/// part (empty only when the exact triangle misses the box). A vertex made by clipping lies
/// exactly on its plane, but its other coordinates err by a few ulps of the triangle's
/// coordinates, and a later plane crossing an edge that runs nearly parallel to it turns that
/// error into a long slide along the edge. So the triangle is clipped to the box widened by pad
/// = 2^-17 of its largest coordinate per axis (64 ulps, far above the few ulps a vertex errs by
/// across the plane), every coordinate a clip computed (not one of the triangle's own, not a
/// plane's) widens the bounds by pad, and the result is cut to the box. Exact coordinates get no
/// pad, so a triangle touching a plane is not spread across it. Without this a triangle whose
/// exact part in a thin cell (1e-17 wide beside coordinates of 0.25) rounded away was never
/// referenced there (tests/clip_test.cpp checks the bounds against an exact clip).
inline Bounds3f clip_triangle_bounds(const Vec3f& a,
                                     const Vec3f& b,
                                     const Vec3f& c,
                                     const Bounds3f& box) {
    struct Vertex {
        Vec3f p;
        unsigned exact;  ///< bit k: coordinate k is exact
    };
    Vec3f pad;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const float mag = std::max({std::abs(a[axis]), std::abs(b[axis]), std::abs(c[axis])});
        pad[axis] = mag * 0x1.0p-17f + 4.0f * std::numeric_limits<float>::denorm_min();
    }
    const Bounds3f wide{box.lo - pad, box.hi + pad};
    // A convex polygon clipped by 6 planes has at most 3 + 6 vertices.
    std::array<Vertex, 9> poly{Vertex{a, 7u}, Vertex{b, 7u}, Vertex{c, 7u}}, next{};
    std::size_t n = 3;
    for (std::size_t axis = 0; axis < 3 && n > 0; ++axis) {
        for (int side = 0; side < 2 && n > 0; ++side) {
            const float plane = side == 0 ? wide.lo[axis] : wide.hi[axis];
            const auto inside = [&](const Vertex& v) {
                return side == 0 ? v.p[axis] >= plane : v.p[axis] <= plane;
            };
            std::size_t m = 0;
            for (std::size_t i = 0; i < n; ++i) {
                const Vertex& p = poly[i];
                const Vertex& q = poly[(i + 1) % n];
                const bool pin = inside(p), qin = inside(q);
                if (pin) {
                    next[m++] = p;
                }
                if (pin != qin && m < next.size()) {
                    const float s = (plane - p.p[axis]) / (q.p[axis] - p.p[axis]);
                    Vec3f x = p.p + (q.p - p.p) * s;
                    x[axis] = plane;  // exactly on the plane despite rounding
                    next[m++] = Vertex{x, 1u << axis};
                }
            }
            poly = next;
            n = m;
        }
    }
    if (n == 0) {
        return Bounds3f{};
    }
    Bounds3f out;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < 3; ++k) {
            const float slack = (poly[i].exact & (1u << k)) != 0 ? 0.0f : pad[k];
            out.lo[k] = std::min(out.lo[k], poly[i].p[k] - slack);
            out.hi[k] = std::max(out.hi[k], poly[i].p[k] + slack);
        }
    }
    return intersection(out, box);
}

/// The part of a triangle inside box, for kd-tree perfect splits. A shape type gets perfect
/// splits in SceneTracer by having a clip_shape_bounds overload.
inline Bounds3f clip_shape_bounds(const Triangle<float>& t, const Bounds3f& box) {
    return clip_triangle_bounds(t.p0, t.p1, t.p2, box);
}

/// |dir.x p.x| + |dir.y p.y| + |dir.z p.z| in double: the magnitude of extent_dot(dir, p)'s terms.
inline double extent_magnitude(const Vec3f& dir, const Vec3f& p) {
    const auto term = [](float d, float x) {
        return std::abs(static_cast<double>(d)) * std::abs(static_cast<double>(x));
    };
    return term(dir.x, p.x) + term(dir.y, p.y) + term(dir.z, p.z);
}

/// A triangle's extent along dir: its vertices', rounded outward. A shape type gets exact extents
/// (ExtentFn) in SceneTracer by having a shape_extent overload.
inline SlabExtent shape_extent(const Triangle<float>& t, const Vec3f& dir) {
    const double d0 = extent_dot(dir, t.p0), d1 = extent_dot(dir, t.p1), d2 = extent_dot(dir, t.p2);
    const double mag = std::max(
        {extent_magnitude(dir, t.p0), extent_magnitude(dir, t.p1), extent_magnitude(dir, t.p2)});
    return outward_extent(std::min({d0, d1, d2}), std::max({d0, d1, d2}), mag);
}

/// A sphere's extent along dir: dot(dir, centre) -+ radius * |dir|, rounded outward.
inline SlabExtent shape_extent(const Sphere<float>& s, const Vec3f& dir) {
    const auto sq = [](float x) { return static_cast<double>(x) * static_cast<double>(x); };
    const double reach =
        static_cast<double>(s.radius) * std::sqrt(sq(dir.x) + sq(dir.y) + sq(dir.z));
    const double c = extent_dot(dir, s.center);
    return outward_extent(c - reach, c + reach, extent_magnitude(dir, s.center) + reach);
}

}  // namespace rtlab
