#pragma once
// Triangle: the shape every triangle intersection method prepares; three vertices, no winding
// convention (methods report hits on both sides).

#include "intersect/bounds.h"
#include "intersect/ray.h"
#include "intersect/vec.h"

#include <cmath>
#include <cstddef>
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

namespace detail {

/// Appends x to the non-overlapping expansion e[0..n) (Shewchuk 1997, Grow-Expansion, with
/// Knuth's TwoSum); returns the new length. The sum of the components is exact.
inline std::size_t grow_expansion(double* e, std::size_t n, double x) {
    for (std::size_t i = 0; i < n; ++i) {
        const double s = x + e[i];
        const double bv = s - x;
        const double err = (x - (s - bv)) + (e[i] - bv);
        e[i] = err;
        x = s;
    }
    e[n] = x;
    return n + 1;
}

/// Adds the exact product a * b (TwoProduct through fma) to the expansion.
inline std::size_t add_product(double* e, std::size_t n, double a, double b) {
    const double p = a * b;
    n = grow_expansion(e, n, std::fma(a, b, -p));
    return grow_expansion(e, n, p);
}

/// True when the 2D orientation of (a, b, c) in axes (i, j) is exactly zero: the sum of six
/// coordinate products, each exact as two doubles, summed without rounding. Exact unless a
/// product underflows (coordinates below about 1e-146).
template <class T>
bool orientation_is_zero(
    const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, std::size_t i, std::size_t j) {
    double e[24];
    std::size_t n = 0;
    const auto d = [](T x) { return static_cast<double>(x); };
    // (b - a)_i (c - a)_j - (b - a)_j (c - a)_i, expanded; the a_i a_j terms cancel.
    n = add_product(e, n, d(b[i]), d(c[j]));
    n = add_product(e, n, -d(b[i]), d(a[j]));
    n = add_product(e, n, -d(a[i]), d(c[j]));
    n = add_product(e, n, -d(b[j]), d(c[i]));
    n = add_product(e, n, d(b[j]), d(a[i]));
    n = add_product(e, n, d(a[j]), d(c[i]));
    for (std::size_t k = 0; k < n; ++k) {
        if (e[k] != 0.0) {
            return false;  // a non-overlapping expansion is zero only when every part is
        }
    }
    return true;
}

}  // namespace detail

/// True when the triangle has exactly zero area (all three vertices on one line, or repeated),
/// decided exactly, not by a rounded cross product. Every method's prepare() uses it so that a
/// zero-area triangle never hits. Cost: 36 exact-sum steps, paid once per triangle.
template <class T>
bool is_degenerate(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2) {
    return detail::orientation_is_zero(p0, p1, p2, 0, 1) &&
           detail::orientation_is_zero(p0, p1, p2, 1, 2) &&
           detail::orientation_is_zero(p0, p1, p2, 2, 0);
}

/// Shared by the methods that keep just the three vertices (Möller–Trumbore, watertight): the
/// shape and prepared types, prepare() and bounds(). A zero-area triangle is stored collapsed to
/// one point, so its determinant is exactly 0 and it never hits.
template <class T>
struct VertexTriangleMethod {
    using Scalar = T;
    using Shape = Triangle<T>;

    /// The vertices as given (collapsed to p0 when the triangle has zero area).
    struct Prepared {
        Vec3<T> p0, p1, p2;
    };

    /// Store the vertices (collapsed to p0 when the triangle has zero area).
    static Prepared prepare(const Shape& s) {
        if (is_degenerate(s.p0, s.p1, s.p2)) {
            return {s.p0, s.p0, s.p0};
        }
        return {s.p0, s.p1, s.p2};
    }

    /// Box around the three vertices.
    static Bounds3<T> bounds(const Prepared& p) { return triangle_bounds(p.p0, p.p1, p.p2); }
};

/// True when t is finite and inside the ray window [tmin, tmax]; false for NaN.
template <class T>
constexpr bool in_window(T t, const Ray<T>& ray) {
    return t >= ray.tmin && t <= ray.tmax && t <= std::numeric_limits<T>::max();
}

}  // namespace rtlab
