#pragma once
// Ray: origin, direction (not necessarily unit) and the parametric window [tmin, tmax].

#include "intersect/vec.h"

#include <limits>

namespace rtlab {

/// A ray org + t * dir for t in [tmin, tmax]; t is measured in units of dir, which need not be
/// normalised. Closest-hit queries shrink tmax as they find hits.
template <class T>
struct Ray {
    Vec3<T> org;
    Vec3<T> dir;
    T tmin = 0;
    T tmax = std::numeric_limits<T>::infinity();

    /// The point at parameter t.
    constexpr Vec3<T> at(T t) const { return org + dir * t; }

    /// Explicit conversion between precisions (float -> double is exact).
    template <class U>
    constexpr explicit operator Ray<U>() const {
        return {Vec3<U>(org), Vec3<U>(dir), static_cast<U>(tmin), static_cast<U>(tmax)};
    }
};

using Rayf = Ray<float>;
using Rayd = Ray<double>;

/// True when the ray can be traced: finite origin and direction, a direction with at least one
/// normal (not denormal, not zero) component, and a window with tmin <= tmax that is not NaN.
/// Traversal rejects other rays before touching any node. Why no denormal-only directions: their
/// reciprocal overflows to infinity, so slab tests would treat the ray as parallel to every axis.
/// Written without branches, as every query runs it: x - x is 0 for a finite x and NaN for an
/// infinite or NaN one, so the six differences sum to 0 exactly when all six are finite; tmin <=
/// tmax is false when either is NaN. Always inlined: GCC left it a call (about 15 more
/// instructions per ray) in the batch loops where the traversal instantiations are largest.
template <class T>
[[gnu::always_inline]] inline bool is_valid(const Ray<T>& r) {
    const Vec3<T> o = r.org - r.org;
    const Vec3<T> d = r.dir - r.dir;
    const bool finite = (o.x + o.y) + (o.z + d.x) + (d.y + d.z) == T(0);
    const bool normal = max_component(abs(r.dir)) >= std::numeric_limits<T>::min();
    return finite & normal & (r.tmin <= r.tmax);
}

}  // namespace rtlab
