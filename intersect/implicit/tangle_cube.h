#pragma once
// Goursat's "tangle cube" x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8 = 0 in local coordinates
// q = (p - centre) / scale; a quartic of genus 5. Cost of the ray polynomial: ~40 multiply-adds.

#include "intersect/bounds.h"
#include "intersect/implicit/poly.h"

#include <cmath>
#include <limits>
#include <string_view>

namespace rtlab {

/// The tangle cube centred at `center`, uniformly scaled by `scale` (> 0).
template <class T>
struct TangleCube {
    using Scalar = T;
    static constexpr std::size_t degree = 4;
    static constexpr std::string_view name = "tangle";

    Vec3<T> center;
    T scale = 1;

    /// Implicit value at p (negative inside the solid).
    T value(const Vec3<T>& p) const {
        const Vec3<T> q = (p - center) / scale;
        T v = T(11.8);
        for (std::size_t k = 0; k < 3; ++k) {
            const T x2 = q[k] * q[k];
            v += x2 * x2 - T(5) * x2;
        }
        return v;
    }

    /// Gradient of value at p.
    Vec3<T> gradient(const Vec3<T>& p) const {
        const Vec3<T> q = (p - center) / scale;
        Vec3<T> g;
        for (std::size_t k = 0; k < 3; ++k) {
            g[k] = (T(4) * q[k] * q[k] * q[k] - T(10) * q[k]) / scale;
        }
        return g;
    }

    /// Box around the surface: each x^4 - 5x^2 >= -6.25, so on the surface x^4 - 5x^2 <= 0.7,
    /// i.e. |x| <= sqrt((5 + sqrt(27.8)) / 2) < 2.2664; bounds are padded to 2.27 scale.
    Bounds3<T> bounds() const {
        constexpr T inf = std::numeric_limits<T>::infinity();
        const T e = T(2.27) * scale;
        Bounds3<T> b;
        for (std::size_t k = 0; k < 3; ++k) {
            b.lo[k] = std::nextafter(center[k] - e, -inf);
            b.hi[k] = std::nextafter(center[k] + e, inf);
        }
        return b;
    }

    /// The quartic f(o + t d) in t: per axis (a + b t)^4 - 5 (a + b t)^2 expanded by the binomial
    /// theorem, in local coordinates a = (o - centre)/scale, b = d/scale.
    Polynomial<T, 4> along(const Vec3<T>& o, const Vec3<T>& d) const {
        Polynomial<T, 4> p;
        p.c[0] = T(11.8);
        for (std::size_t k = 0; k < 3; ++k) {
            const T a = (o[k] - center[k]) / scale, b = d[k] / scale;
            const T a2 = a * a, b2 = b * b;
            p.c[0] += a2 * a2 - T(5) * a2;
            p.c[1] += T(4) * a2 * a * b - T(10) * a * b;
            p.c[2] += T(6) * a2 * b2 - T(5) * b2;
            p.c[3] += T(4) * a * b2 * b;
            p.c[4] += b2 * b2;
        }
        return p;
    }
};

}  // namespace rtlab
