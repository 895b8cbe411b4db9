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

/// The box itself: the slab methods' prepared form and bounds.
template <class T>
Bounds3<T> same_box(const Bounds3<T>& b) {
    return b;
}

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

/// What both slab methods share (derive from it, CRTP): the box as shape, prepared form and
/// bounds, the reciprocal direction (SlabRay) as per-ray set-up, and intersect as
/// detail::aabb_intersect<IsRobust>. A method adds its name.
template <class Self, class T, bool IsRobust>
struct AabbMethodBase : FamilyRayMethod<Self,
                                        T,
                                        Bounds3<T>,
                                        Bounds3<T>,
                                        detail::same_box<T>,
                                        detail::same_box<T>,
                                        SlabRay<T>> {
    using MethodDefaults<Self>::intersect;

    /// Entry t of the window [tmin, tmax] into the closed box (tmin when the origin is inside;
    /// robust: padded down by up to 2*gamma(3) relative); u = v = 0.
    static std::optional<PrimHit<T>> intersect(const Bounds3<T>& p,
                                               const Ray<T>& ray,
                                               const SlabRay<T>& r) {
        return detail::aabb_intersect<IsRobust>(p, ray, r);
    }
};

/// Fast slab test: exact IEEE reciprocals, no padding; may miss boxes grazed within rounding.
template <class T>
struct AabbSlabs : AabbMethodBase<AabbSlabs<T>, T, false> {
    static constexpr std::string_view name = "slabs";
};

/// Robust slab test (Ize 2013): the computed interval contains the exact one, so a box the exact
/// ray touches is never missed; boxes missed by a few ulps may be reported as hits.
template <class T>
struct AabbSlabsRobust : AabbMethodBase<AabbSlabsRobust<T>, T, true> {
    static constexpr std::string_view name = "slabs_robust";
};

}  // namespace rtlab
