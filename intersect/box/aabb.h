#pragma once
// Ray-AABB slab test (Kay & Kajiya 1986; Williams et al. 2005) on intersect/box/slabs.h. "slabs"
// uses the IEEE reciprocal (zero direction components give +-inf, no epsilon); "slabs_robust"
// widens the slab distances by 2*gamma(3) (Ize 2013). Cost: 3 div per ray (precompute: the
// reciprocal direction), then 6 mul, 6 sub per box.

#include "intersect/box/slabs.h"
#include "intersect/hit.h"
#include "intersect/method.h"

#include <optional>
#include <string_view>

namespace rtlab {

namespace detail {

/// Slab test of the closed box b for the ray window, with sr = SlabRay(ray); the hit t is the
/// entry (tmin when inside).
template <bool IsRobust, class T>
std::optional<PrimHit<T>> aabb_intersect(const Bounds3<T>& b,
                                         const Ray<T>& ray,
                                         const SlabRay<T>& sr) {
    T tnear;
    if (!slab_hit<IsRobust>(b, sr, ray.tmin, ray.tmax, tnear)) {
        return std::nullopt;
    }
    return PrimHit<T>{tnear, T(0), T(0)};
}

}  // namespace detail

/// Fast slab test: exact IEEE reciprocals, no padding; may miss boxes grazed within rounding.
template <class T>
struct AabbSlabs : MethodDefaults<AabbSlabs<T>> {
    using MethodDefaults<AabbSlabs<T>>::intersect;
    using Scalar = T;
    using Shape = Bounds3<T>;
    using Prepared = Bounds3<T>;
    /// The per-ray set-up: reciprocal direction and direction signs.
    using RayData = SlabRay<T>;
    static constexpr std::string_view name = "slabs";

    /// The box itself.
    static Prepared prepare(const Shape& s) { return s; }
    /// The box itself.
    static Bounds3<T> bounds(const Prepared& p) { return p; }
    /// The reciprocal direction of ray (once per ray, shared by every box).
    static RayData precompute(const Ray<T>& ray) { return RayData(ray); }
    /// Entry t of the window [tmin, tmax] into the closed box (tmin when the origin is inside);
    /// u = v = 0.
    static std::optional<PrimHit<T>> intersect(const Prepared& p,
                                               const Ray<T>& ray,
                                               const RayData& r) {
        return detail::aabb_intersect<false>(p, ray, r);
    }
};

/// Robust slab test (Ize 2013): the computed interval contains the exact one, so a box the exact
/// ray touches is never missed; boxes missed by a few ulps may be reported as hits.
template <class T>
struct AabbSlabsRobust : MethodDefaults<AabbSlabsRobust<T>> {
    using MethodDefaults<AabbSlabsRobust<T>>::intersect;
    using Scalar = T;
    using Shape = Bounds3<T>;
    using Prepared = Bounds3<T>;
    /// The per-ray set-up: reciprocal direction and direction signs.
    using RayData = SlabRay<T>;
    static constexpr std::string_view name = "slabs_robust";

    /// The box itself.
    static Prepared prepare(const Shape& s) { return s; }
    /// The box itself.
    static Bounds3<T> bounds(const Prepared& p) { return p; }
    /// The reciprocal direction of ray (once per ray, shared by every box).
    static RayData precompute(const Ray<T>& ray) { return RayData(ray); }
    /// Entry t (padded down by up to 2*gamma(3) relative; tmin when inside); u = v = 0.
    static std::optional<PrimHit<T>> intersect(const Prepared& p,
                                               const Ray<T>& ray,
                                               const RayData& r) {
        return detail::aabb_intersect<true>(p, ray, r);
    }
};

}  // namespace rtlab
