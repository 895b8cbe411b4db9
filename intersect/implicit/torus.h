#pragma once
// Torus about the z axis: f(p) = (|q|^2 + R^2 - r^2)^2 - 4 R^2 (qx^2 + qy^2) with q = p - centre,
// a quartic; f < 0 inside the tube. Cost of the ray polynomial: ~25 multiply-adds.

#include "intersect/bounds.h"
#include "intersect/implicit/poly.h"

#include <cmath>
#include <limits>
#include <string_view>

namespace rtlab {

/// Torus of major radius `major` (centre to tube centre) and minor radius `minor` (tube), axis z.
template <class T>
struct Torus {
    using Scalar = T;
    static constexpr std::size_t degree = 4;
    static constexpr std::string_view name = "torus";

    Vec3<T> center;
    T major = 1;
    T minor = T(0.25);

    /// Implicit value at p (negative inside the tube).
    T value(const Vec3<T>& p) const {
        const Vec3<T> q = p - center;
        const T k = dot(q, q) + major * major - minor * minor;
        return k * k - T(4) * major * major * (q.x * q.x + q.y * q.y);
    }

    /// Gradient of value at p (outward on the surface).
    Vec3<T> gradient(const Vec3<T>& p) const {
        const Vec3<T> q = p - center;
        const T k = dot(q, q) + major * major - minor * minor;
        const T rr = T(2) * major * major;
        return {T(4) * q.x * (k - rr), T(4) * q.y * (k - rr), T(4) * q.z * k};
    }

    /// Box around the torus, each bound moved one ulp outwards against rounding.
    Bounds3<T> bounds() const {
        constexpr T inf = std::numeric_limits<T>::infinity();
        const Vec3<T> e{major + minor, major + minor, minor};
        Bounds3<T> b;
        for (std::size_t k = 0; k < 3; ++k) {
            b.lo[k] = std::nextafter(std::nextafter(center[k] - e[k], -inf), -inf);
            b.hi[k] = std::nextafter(std::nextafter(center[k] + e[k], inf), inf);
        }
        return b;
    }

    /// The quartic f(o + t d) in t, coefficients from expanding the ray into f.
    Polynomial<T, 4> along(const Vec3<T>& o, const Vec3<T>& d) const {
        const Vec3<T> q = o - center;
        const T a = dot(d, d), b = T(2) * dot(q, d), c = dot(q, q) + major * major - minor * minor;
        const T r4 = T(4) * major * major;
        const T ea = d.x * d.x + d.y * d.y;
        const T eb = T(2) * (q.x * d.x + q.y * d.y);
        const T ec = q.x * q.x + q.y * q.y;
        return {{c * c - r4 * ec, T(2) * b * c - r4 * eb, b * b + T(2) * a * c - r4 * ea,
                 T(2) * a * b, a * a}};
    }
};

}  // namespace rtlab
