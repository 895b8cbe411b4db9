#pragma once
// The intersection-method concept: a stateless struct that prepares a shape once and then tests
// rays against the prepared form. The same shape can be tested by every method of its kind.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/ray.h"

#include <concepts>
#include <optional>
#include <string_view>

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

}  // namespace rtlab
