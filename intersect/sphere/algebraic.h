#pragma once
// Algebraic ray-sphere test: substitute the ray into |p - c|^2 = r^2 and use the textbook formula
// t = (-b -+ sqrt(b^2 - 4ac)) / 2a. No epsilon. Cancellation in b^2 - 4ac when the sphere is small
// and far (relative error ~ eps (D/r)^2). Cost: 2 dot products, 1 sqrt, 2 divisions
// per test, plus a = d.d once per ray (precompute).

#include "intersect/method.h"
#include "intersect/sphere/sphere.h"

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// Algebraic method: the quadratic formula on a t^2 + b t + c.
template <class T>
struct SphereAlgebraic : MethodDefaults<SphereAlgebraic<T>> {
    using MethodDefaults<SphereAlgebraic<T>>::intersect;
    using Scalar = T;
    using Shape = Sphere<T>;
    using Prepared = PreparedSphere<T>;
    /// The per-ray set-up: a = dir . dir.
    using RayData = SphereRay<T>;
    static constexpr std::string_view name = "algebraic";

    /// Copies centre and radius and squares the radius.
    static Prepared prepare(const Shape& s) { return detail::prepare_sphere(s); }
    /// Conservative box around the sphere.
    static Bounds3<T> bounds(const Prepared& p) { return detail::sphere_bounds(p); }
    /// a = dir . dir of ray (once per ray, shared by every sphere).
    static RayData precompute(const Ray<T>& ray) { return SphereRay<T>::make(ray); }

    /// Entering and leaving t (unclipped, entering <= leaving), or nullopt when the line misses.
    static std::optional<std::pair<T, T>> roots(const Prepared& p,
                                                const Ray<T>& ray,
                                                const RayData& rd) {
        const Vec3<T> f = ray.org - p.center;
        const T a = rd.a;
        const T b = T(2) * dot(f, ray.dir);
        const T c = dot(f, f) - p.radius2;
        const T disc = b * b - T(4) * a * c;
        if (disc < T(0)) {
            return std::nullopt;
        }
        const T s = std::sqrt(disc);
        return std::pair<T, T>{(-b - s) / (T(2) * a), (-b + s) / (T(2) * a)};
    }

    /// Nearest t in [tmin, tmax]; the leaving root when the origin is inside.
    static std::optional<PrimHit<T>> intersect(const Prepared& p,
                                               const Ray<T>& ray,
                                               const RayData& rd) {
        return detail::pick_root(roots(p, ray, rd), ray);
    }
};

}  // namespace rtlab
