#pragma once
// Algebraic ray-sphere test: substitute the ray into |p - c|^2 = r^2 and use the textbook formula
// t = (-b -+ sqrt(b^2 - 4ac)) / 2a. No epsilon. Cancellation in b^2 - 4ac when the sphere is small
// and far (relative error ~ eps (D/r)^2). Cost: 2 dot products, 1 sqrt, 2 divisions
// per test, plus a = d.d once per ray (precompute).

#include "intersect/sphere/sphere.h"

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// Algebraic method: the quadratic formula on a t^2 + b t + c.
template <class T>
struct SphereAlgebraic : SphereMethodBase<SphereAlgebraic<T>, T> {
    static constexpr std::string_view name = "algebraic";

    /// Entering and leaving t (unclipped, entering <= leaving), or nullopt when the line misses.
    static std::optional<std::pair<T, T>> roots(const PreparedSphere<T>& p,
                                                const Ray<T>& ray,
                                                const SphereRay<T>& rd) {
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
};

}  // namespace rtlab
