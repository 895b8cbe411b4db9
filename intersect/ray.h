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
template <class T>
bool is_valid(const Ray<T>& r) {
    return is_finite(r.org) && is_finite(r.dir) &&
           max_component(abs(r.dir)) >= std::numeric_limits<T>::min() && !(r.tmin != r.tmin) &&
           !(r.tmax != r.tmax) && r.tmin <= r.tmax;
}

}  // namespace rtlab
