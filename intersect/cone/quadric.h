#pragma once
// Closed-form ray/cone test in world space: substitute the ray into the quadric
// |w|^2 - (w.a)^2 = (r0 + k w.a)^2 (w = p - base, a the unit axis, k the radius slope), solve
// A t^2 + 2 B t + C = 0 by the textbook formula t = (-B -+ sqrt(B^2 - A C)) / A, keep roots with
// 0 <= w.a <= height, then the cap planes. No epsilon. Cancellation in B^2 - A C when the cone is
// far from the origin relative to its size (relative error ~ eps (D/r)^2), and in A for rays
// nearly parallel to a generator. Cost: 4 dot products, 1 sqrt, 2 divisions; dd = d.d per ray.

#include "intersect/cone/cone.h"

#include <cmath>
#include <optional>
#include <string_view>

namespace rtlab {

/// The quadric in closed form, in world coordinates.
template <class T>
struct ConeQuadric : ConeMethodBase<ConeQuadric<T>, T> {
    using ConeMethodBase<ConeQuadric<T>, T>::intersect;
    static constexpr std::string_view name = "quadric";

    /// Nearest t in [tmin, tmax] on the side or a cap; u: 0 side, 1 base cap, 2 apex cap; v: the
    /// hit's position along the axis (0 base, 1 apex).
    static std::optional<PrimHit<T>> intersect(const PreparedCone<T>& p,
                                               const Ray<T>& ray,
                                               const ConeRay<T>& rd) {
        const Vec3<T> w = ray.org - p.base;
        const T sd = dot(ray.dir, p.axis);  // axial speed
        const T s0 = dot(w, p.axis);        // axial position of the origin
        const T k = p.slope;
        const T rw = p.r0 + k * s0;  // radius at the origin's axial position
        const T a = rd.dd - (T(1) + k * k) * sd * sd;
        const T b = dot(w, ray.dir) - s0 * sd - k * sd * rw;
        const T c = dot(w, w) - s0 * s0 - rw * rw;
        std::optional<PrimHit<T>> best;
        const auto side = [&](T t) {
            const T s = s0 + t * sd;
            if (s >= T(0) && s <= p.height) {
                detail::keep_nearest(best, t, T(0), s / p.height, ray);
            }
        };
        if (a == T(0)) {
            // Parallel to a generator (or, for a cylinder, to the axis): one root at most.
            if (b != T(0)) {
                side(-c / (T(2) * b));
            }
        } else {
            const T disc = b * b - a * c;
            if (disc >= T(0)) {
                const T sq = std::sqrt(disc);
                side((-b - sq) / a);
                side((-b + sq) / a);
            }
        }
        detail::cap_hits(p, ray, s0, sd, best);
        return best;
    }
};

}  // namespace rtlab
