#pragma once
// Triangle: the shape every triangle intersection method prepares; three vertices, no winding
// convention (methods report hits on both sides).

#include "intersect/bounds.h"
#include "intersect/ray.h"
#include "intersect/vec.h"

#include <limits>

namespace rtlab {

/// A triangle p0, p1, p2; a hit point is (1 - u - v) * p0 + u * p1 + v * p2.
template <class T>
struct Triangle {
    Vec3<T> p0, p1, p2;
};

using Trianglef = Triangle<float>;
using Triangled = Triangle<double>;

/// Smallest box containing the three vertices (exact: only min and max are taken).
template <class T>
constexpr Bounds3<T> triangle_bounds(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2) {
    return Bounds3<T>(p0).extend(p1).extend(p2);
}

/// True when the edge cross product (p1 - p0) x (p2 - p0), evaluated in T, is exactly zero: the
/// test every method's prepare() uses to turn a zero-area triangle into one that never hits.
template <class T>
constexpr bool is_degenerate(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2) {
    const Vec3<T> n = cross(p1 - p0, p2 - p0);
    return n.x == T(0) && n.y == T(0) && n.z == T(0);
}

/// True when t is finite and inside the ray window [tmin, tmax]; false for NaN.
template <class T>
constexpr bool in_window(T t, const Ray<T>& ray) {
    return t >= ray.tmin && t <= ray.tmax && t <= std::numeric_limits<T>::max();
}

}  // namespace rtlab
