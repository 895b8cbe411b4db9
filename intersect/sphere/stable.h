#pragma once
// Haines, Guenther, Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection", Ray
// Tracing Gems (2019) ch. 7: discriminant from the centre's distance to the ray's line (Hearn &
// Baker), roots by q = -(b + sign(b) sqrt(disc)), t0 = q/a, t1 = c/q. No epsilon. Cost: 3 dots
// per test, plus a = d.d once per ray (precompute).

#include "intersect/sphere/sphere.h"

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// Numerically stable method: perpendicular-distance discriminant and the stable root pair.
template <class T>
struct SphereStable : SphereMethodBase<SphereStable<T>, T> {
    static constexpr std::string_view name = "stable";

    /// Entering and leaving t (unclipped, entering <= leaving), or nullopt when the line misses.
    static std::optional<std::pair<T, T>> roots(const PreparedSphere<T>& p,
                                                const Ray<T>& ray,
                                                const SphereRay<T>& rd) {
        // a t^2 + 2 h t + c = 0 with h = f.d (half the usual b), f = origin - centre.
        const Vec3<T> f = ray.org - p.center;
        const T a = rd.a;
        const T h = dot(f, ray.dir);
        const T c = dot(f, f) - p.radius2;
        // h^2 - a c = a (r^2 - |f_perp|^2): f_perp = f - (h/a) d is the centre's offset from the
        // line; its squared length has error ~eps D^2 instead of the eps D^4 of h^2 - a c.
        const Vec3<T> f_perp = f - ray.dir * (h / a);
        const T disc = a * (p.radius2 - dot(f_perp, f_perp));
        if (disc < T(0)) {
            return std::nullopt;
        }
        // q has the sign of -h, so h + sign(h) sqrt(disc) never cancels.
        const T q = -(h + std::copysign(std::sqrt(disc), h));
        const T t0 = q / a;
        const T t1 = q != T(0) ? c / q : t0;  // q == 0 only for a tangent line through the origin
        return t0 <= t1 ? std::pair<T, T>{t0, t1} : std::pair<T, T>{t1, t0};
    }
};

}  // namespace rtlab
