#pragma once
// Ray: origin, direction (not necessarily unit) and the parametric window [tmin, tmax].

#include <limits>

#include "intersect/vec.h"

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

/// True when the ray can be traced: finite origin and direction, non-zero direction, and a window
/// with tmin <= tmax that is not NaN. Traversal rejects other rays before touching any node.
template <class T>
bool is_valid(const Ray<T>& r) {
    return is_finite(r.org) && is_finite(r.dir) && length_squared(r.dir) > T(0) &&
           !(r.tmin != r.tmin) && !(r.tmax != r.tmax) && r.tmin <= r.tmax;
}

}  // namespace rtlab
