#pragma once
// Geometric ray-sphere test with early outs (seed 000, "Schnitt Strahl-Kugel"; also Haines 1989
// in Glassner, "An Introduction to Ray Tracing"). Generalised to non-unit directions by dividing
// by a = d.d. No epsilon: the seed's `m^2 - r^2 > eps` choice is replaced by taking the nearest
// root in [tmin, tmax]. Cost: 2 dot products, early reject before the square root; a = d.d
// once per ray (precompute).

#include "intersect/sphere/sphere.h"

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace rtlab {

/// Geometric method: vector to the centre, its projection on the ray, early rejects.
template <class T>
struct SphereGeometric : SphereMethodBase<SphereGeometric<T>, T>, SphereLaneForm<T> {
    using SphereMethodBase<SphereGeometric<T>, T>::intersect;
    static constexpr std::string_view name = "geometric";

    /// Entering and leaving t (unclipped, entering <= leaving), or nullopt when the line misses.
    static std::optional<std::pair<T, T>> roots(const PreparedSphere<T>& p,
                                                const Ray<T>& ray,
                                                const SphereRay<T>& rd) {
        return SphereLaneForm<T>::scalar(roots_on<T>(p, ray, rd, false));
    }

    /// Nearest t in [tmin, tmax]; the leaving root when the origin is inside.
    static std::optional<PrimHit<T>> intersect(const PreparedSphere<T>& p,
                                               const Ray<T>& ray,
                                               const SphereRay<T>& rd) {
        const LaneHit<T> h = test<T>(p, ray, rd);
        return h.hit ? std::optional(PrimHit<T>{h.t}) : std::nullopt;
    }

    /// roots on one sphere (L = T, P = PreparedSphere) or on lanes (L = FloatLanes, P = Lanes);
    /// with early_out, not where the seed's early out rejects (as test does).
    template <class L, class P>
    static SphereRoots<L> roots_on(const P& p,
                                   const Ray<T>& ray,
                                   const SphereRay<T>& rd,
                                   bool early_out) {
        SphereRoots<L> r;
        const auto m = p.center - splat3<L>(ray.org);  // origin -> centre
        const L b = dot(m, splat3<L>(ray.dir));        // a * (projection of the centre on the ray)
        const L c = dot(m, m) - p.radius2;             // > 0: origin outside
        // Early out of the seed: origin outside and the centre behind means both roots are < 0;
        // only valid when the window starts at or after the origin.
        r.ok = early_out && ray.tmin >= T(0) ? lane_not((c >= T(0)) & (b <= T(0))) : all_set<L>();
        if (none(r.ok)) {
            return r;
        }
        const T a = rd.a;
        const L disc = b * b - a * c;  // a^2 * squared half chord
        r.ok = r.ok & lane_not(disc < T(0));
        if (none(r.ok)) {
            return r;
        }
        const L s = lane_sqrt(disc);
        r.near = (b - s) / a;
        r.far = (b + s) / a;
        return r;
    }

    /// intersect on one sphere or on lanes: the nearest root in the window, after the early out.
    template <class L, class P>
    static LaneHit<L> test(const P& p, const Ray<T>& ray, const SphereRay<T>& rd) {
        return pick_root(roots_on<L>(p, ray, rd, true), ray);
    }
};

}  // namespace rtlab
