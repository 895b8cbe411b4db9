#pragma once
// The intersection-method concept: a stateless struct that prepares a shape once and then tests
// rays against the prepared form. The same shape can be tested by every method of its kind.
//
// Per-ray set-up: a method may declare `using RayData = ...;` with
// `static RayData precompute(const Ray<Scalar>&)` and the overloads
// `intersect(prepared, ray, ray_data)` / `occluded(prepared, ray, ray_data)`; MethodDefaults
// supplies the forms a method does not write. Callers that test
// one ray against many primitives (traversal, benchmarks) call precompute once per ray through
// precompute_ray<M>() and then intersect_with<M>() / occluded_with<M>(); methods without set-up
// get an empty NoRayData and the two-argument calls. RayData depends on the ray's origin and
// direction only, never on its window [tmin, tmax], so it stays valid while a closest-hit
// traversal shrinks tmax; with it, every answer is bit-identical to the two-argument call.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/ray.h"

#include <array>
#include <concepts>
#include <cstddef>
#include <optional>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

namespace rtlab {

/// A method that can answer hit / no-hit for a ray window [tmin, tmax].
template <class M>
concept OcclusionMethod = requires(const typename M::Shape& s,
                                   const typename M::Prepared& p,
                                   const Ray<typename M::Scalar>& r) {
    { M::name } -> std::convertible_to<std::string_view>;
    { M::prepare(s) } -> std::same_as<typename M::Prepared>;
    { M::bounds(p) } -> std::same_as<Bounds3<typename M::Scalar>>;
    { M::occluded(p, r) } -> std::same_as<bool>;
};

/// A method that also reports the nearest hit parameter t in [tmin, tmax] (plus u, v).
template <class M>
concept IntersectionMethod = OcclusionMethod<M> &&
    requires(const typename M::Prepared& p, const Ray<typename M::Scalar>& r) {
    { M::intersect(p, r) } -> std::same_as<std::optional<PrimHit<typename M::Scalar>>>;
};

/// A method with per-ray set-up (see the file comment): precompute once, test many primitives.
template <class M>
concept HasRayData = OcclusionMethod<M> && requires(const typename M::Prepared& p,
                                                    const Ray<typename M::Scalar>& r,
                                                    const typename M::RayData& d) {
    { M::precompute(r) } -> std::same_as<typename M::RayData>;
    { M::occluded(p, r, d) } -> std::same_as<bool>;
};

/// What a method need not write (derive from it, CRTP): occluded() as "intersect() reports a hit"
/// in both forms, and, for a method with per-ray set-up, intersect(p, ray) as intersect(p, ray,
/// precompute(ray)). A method writes its own only where it is cheaper (an occlusion-only method,
/// an early out); one that writes only the three-argument intersect adds
/// `using MethodDefaults<Self>::intersect;`.
template <class Self>
struct MethodDefaults {
    /// Same as intersect(p, ray, precompute(ray)).
    template <class P, class R>
    static auto intersect(const P& p, const R& ray) {
        return Self::intersect(p, ray, Self::precompute(ray));
    }
    /// True when intersect() would report a hit.
    template <class P, class R>
    static bool occluded(const P& p, const R& ray) {
        return Self::intersect(p, ray).has_value();
    }
    /// Same as occluded(p, ray) with d = precompute(ray).
    template <class P, class R, class D>
    static bool occluded(const P& p, const R& ray, const D& d) {
        return Self::intersect(p, ray, d).has_value();
    }
};

/// What the methods of one shape family share (derive from it, CRTP, or from the family's base
/// built on it): the scalar, shape and prepared types, and prepare and bounds as the family's
/// functions PrepareFn(shape) and BoundsFn(prepared), so a method writes only its name and tests.
template <class Self, class T, class ShapeT, class PreparedT, auto PrepareFn, auto BoundsFn>
struct FamilyMethod : MethodDefaults<Self> {
    using Scalar = T;
    using Shape = ShapeT;
    using Prepared = PreparedT;

    /// The family's prepared form of s.
    static Prepared prepare(const Shape& s) { return PrepareFn(s); }
    /// The family's conservative box around p.
    static Bounds3<T> bounds(const Prepared& p) { return BoundsFn(p); }
};

/// FamilyMethod for a family with per-ray set-up (see the file comment): RayData, made once per
/// ray by RayData::make(ray).
template <class Self,
          class T,
          class ShapeT,
          class PreparedT,
          auto PrepareFn,
          auto BoundsFn,
          class RayDataT>
struct FamilyRayMethod : FamilyMethod<Self, T, ShapeT, PreparedT, PrepareFn, BoundsFn> {
    using RayData = RayDataT;

    /// The family's per-ray set-up of ray (once per ray, shared by every primitive).
    static RayData precompute(const Ray<T>& ray) { return RayData::make(ray); }
};

/// The per-ray data of methods without set-up.
struct NoRayData {};

namespace detail {
template <class M>
struct RayDataOf {
    using type = NoRayData;
};
template <HasRayData M>
struct RayDataOf<M> {
    using type = typename M::RayData;
};
}  // namespace detail

/// M::RayData, or NoRayData for a method without per-ray set-up.
template <class M>
using RayDataOf = typename detail::RayDataOf<M>::type;

/// Runs M's per-ray set-up (nothing for methods without one). Call once per ray.
template <class M>
RayDataOf<M> precompute_ray(const Ray<typename M::Scalar>& ray) {
    if constexpr (HasRayData<M>) {
        return M::precompute(ray);
    } else {
        return {};
    }
}

/// M::intersect with the ray's precomputed data (d from precompute_ray<M>(ray)).
template <IntersectionMethod M>
std::optional<PrimHit<typename M::Scalar>> intersect_with(const typename M::Prepared& p,
                                                          const Ray<typename M::Scalar>& ray,
                                                          const RayDataOf<M>& d) {
    if constexpr (HasRayData<M>) {
        return M::intersect(p, ray, d);
    } else {
        return M::intersect(p, ray);
    }
}

/// M::occluded with the ray's precomputed data (d from precompute_ray<M>(ray)).
template <OcclusionMethod M>
bool occluded_with(const typename M::Prepared& p,
                   const Ray<typename M::Scalar>& ray,
                   const RayDataOf<M>& d) {
    if constexpr (HasRayData<M>) {
        return M::occluded(p, ray, d);
    } else {
        return M::occluded(p, ray);
    }
}

/// Calls f.template operator()<M>() for each type M of the std::tuple type List, in order. The
/// method lists in intersect/*/methods.h are such tuples.
template <class List, class F>
void for_each_type(F&& f) {
    [&]<class... Ms>(std::tuple<Ms...>*) {
        (f.template operator()<Ms>(), ...);
    }(static_cast<List*>(nullptr));
}

namespace detail {
template <class List>
struct IntersectorsOf;
template <class... Ms>
struct IntersectorsOf<std::tuple<Ms...>> {
    using type = decltype(std::tuple_cat(
        std::declval<
            std::conditional_t<IntersectionMethod<Ms>, std::tuple<Ms>, std::tuple<>>>()...));
};
}  // namespace detail

/// The methods of the std::tuple list List that report t (satisfy IntersectionMethod), in order.
template <class List>
using IntersectorsOf = typename detail::IntersectorsOf<List>::type;

/// True when no two methods of the std::tuple list List share a name (names select methods on
/// the command line and label every output row).
template <class List>
consteval bool names_unique() {
    return []<class... Ms>(std::tuple<Ms...>*) {
        const std::array<std::string_view, sizeof...(Ms)> names{Ms::name...};
        for (std::size_t i = 0; i < names.size(); ++i) {
            for (std::size_t j = i + 1; j < names.size(); ++j) {
                if (names[i] == names[j]) {
                    return false;
                }
            }
        }
        return true;
    }(static_cast<List*>(nullptr));
}

}  // namespace rtlab
