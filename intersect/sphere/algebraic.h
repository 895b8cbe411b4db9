#pragma once
// Algebraic ray-sphere test: substitute the ray into |p - c|^2 = r^2 and use the textbook formula
// t = (-b -+ sqrt(b^2 - 4ac)) / 2a. No epsilon. Cancellation in b^2 - 4ac when the sphere is small
// and far (relative error ~ eps (D/r)^2). Cost: 2 dot products, 1 sqrt, 2 divisions
// per test, plus a = d.d once per ray (precompute).

#include "intersect/lanes.h"
#include "intersect/sphere/sphere.h"

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// Algebraic method: the quadratic formula on a t^2 + b t + c.
template <class T>
struct SphereAlgebraic : SphereMethodBase<SphereAlgebraic<T>, T>, SphereLaneForm<T> {
    static constexpr std::string_view name = "algebraic";

    /// Entering and leaving t (unclipped, entering <= leaving), or nullopt when the line misses.
    static std::optional<std::pair<T, T>> roots(const PreparedSphere<T>& p,
                                                const Ray<T>& ray,
                                                const SphereRay<T>& rd) {
        return SphereLaneForm<T>::scalar(roots_on<T>(p, ray, rd));
    }

    /// roots on one sphere (L = T, P = PreparedSphere) or on lanes (L = FloatLanes, P = Lanes).
    template <class L, class P>
    static SphereRoots<L> roots_on(const P& p, const Ray<T>& ray, const SphereRay<T>& rd) {
        SphereRoots<L> r;
        const auto f = splat3<L>(ray.org) - p.center;
        const T a = rd.a;
        const L b = T(2) * dot(f, splat3<L>(ray.dir));
        const L c = dot(f, f) - p.radius2;
        const L disc = b * b - T(4) * a * c;
        r.ok = lane_not(disc < T(0));
        if (none(r.ok)) {
            return r;
        }
        const L s = lane_sqrt(disc);
        r.near = (-b - s) / (T(2) * a);
        r.far = (-b + s) / (T(2) * a);
        return r;
    }

    /// The nearest root in the window on lanes (and, through roots, on one sphere).
    template <class L, class P>
    static LaneHit<L> test(const P& p, const Ray<T>& ray, const SphereRay<T>& rd) {
        return pick_root(roots_on<L>(p, ray, rd), ray);
    }
};

}  // namespace rtlab
