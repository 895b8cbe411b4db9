#pragma once
// Ray-OBB slab test (Möller & Haines, "Real-Time Rendering"; Kay & Kajiya 1986): origin and
// direction projected on each axis; no epsilon, a slab with dot(d, axis) == 0 is decided by the
// origin. Cost: 3 sub, 6 dot products, 6 div.

#include "intersect/box/slabs.h"
#include "intersect/hit.h"
#include "intersect/method.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// An oriented box: points c + sum_i s_i * axis[i] with |s_i| <= half[i]; axes orthonormal,
/// half extents >= 0.
template <class T>
struct Obb {
    Vec3<T> center;
    Vec3<T> axis[3];
    Vec3<T> half;
};

/// Slab test along the three box axes.
template <class T>
struct ObbSlabs : MethodDefaults<ObbSlabs<T>> {
    using Scalar = T;
    using Shape = Obb<T>;
    using Prepared = Obb<T>;
    static constexpr std::string_view name = "obb_slabs";

    /// The box itself.
    static Prepared prepare(const Shape& s) { return s; }

    /// Axis-aligned box around the OBB, widened by a few ulps so rounding never makes it smaller
    /// than the exact one.
    static Bounds3<T> bounds(const Prepared& p) {
        Vec3<T> ext;
        for (std::size_t k = 0; k < 3; ++k) {
            ext[k] = std::abs(p.axis[0][k]) * p.half[0] + std::abs(p.axis[1][k]) * p.half[1] +
                     std::abs(p.axis[2][k]) * p.half[2];
        }
        ext *= T(1) + gamma_bound<T>(6);  // 5 rounded ops per component, plus the sums below
        Bounds3<T> b(p.center - ext, p.center + ext);
        for (std::size_t k = 0; k < 3; ++k) {
            b.lo[k] = std::nextafter(b.lo[k], -std::numeric_limits<T>::infinity());
            b.hi[k] = std::nextafter(b.hi[k], std::numeric_limits<T>::infinity());
        }
        return b;
    }

    /// Entry t of the window [tmin, tmax] into the closed box (tmin when the origin is inside);
    /// u = v = 0.
    static std::optional<PrimHit<T>> intersect(const Prepared& p, const Ray<T>& ray) {
        const Vec3<T> m = ray.org - p.center;
        T t0 = ray.tmin, t1 = ray.tmax;
        for (std::size_t i = 0; i < 3; ++i) {
            const T e = dot(m, p.axis[i]);        // origin's coordinate along the axis
            const T f = dot(ray.dir, p.axis[i]);  // direction's coordinate along the axis
            const T h = p.half[i];
            if (f == T(0)) {
                // Parallel to the slab: the whole line is inside or outside it (no 0/0 NaN).
                if (e < -h || e > h) {
                    return std::nullopt;
                }
                continue;
            }
            // Division rather than a reciprocal: f may be denormal (1/f = inf would turn an
            // origin on the face plane into 0 * inf = NaN); (+-h - e) / f is then +-inf or 0.
            T tn = (-h - e) / f;
            T tf = (h - e) / f;
            if (tn > tf) {
                std::swap(tn, tf);
            }
            t0 = tn > t0 ? tn : t0;
            t1 = tf < t1 ? tf : t1;
            if (t0 > t1) {
                return std::nullopt;
            }
        }
        return PrimHit<T>{t0, T(0), T(0)};
    }
};

}  // namespace rtlab
