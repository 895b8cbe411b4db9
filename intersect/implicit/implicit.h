#pragma once
// Shared frame of the implicit-surface methods (seed 000, "Schnitt Strahl - implizite Flaeche"):
// clip the ray to the surface's box (slabs), re-parametrise the window as u in [0, 1] so the ray
// polynomial is well scaled, find the first root u there, map back to t.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/implicit/poly.h"
#include "intersect/ray.h"

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <utility>

namespace rtlab {

/// A polynomial implicit surface f(p) = 0: value, gradient, a box containing the zero set and
/// the exact univariate polynomial f(o + t d) in t.
template <class S>
concept ImplicitSurface = requires(const S& s, const Vec3<typename S::Scalar>& v) {
    { s.value(v) } -> std::same_as<typename S::Scalar>;
    { s.gradient(v) } -> std::same_as<Vec3<typename S::Scalar>>;
    { s.bounds() } -> std::same_as<Bounds3<typename S::Scalar>>;
    { s.along(v, v) } -> std::same_as<Polynomial<typename S::Scalar, S::degree>>;
};

/// What the implicit methods prepare: the surface and its box.
template <class S>
struct PreparedImplicit {
    S surface;
    Bounds3<typename S::Scalar> box;
};

/// What the implicit methods prepare of surface s: s and its box.
template <class S>
PreparedImplicit<S> prepare_implicit(const S& s) {
    return {s, s.bounds()};
}

/// The box of a prepared surface.
template <class S>
Bounds3<typename S::Scalar> implicit_box(const PreparedImplicit<S>& p) {
    return p.box;
}

/// The per-ray set-up of the implicit methods: the reciprocal direction for the box clip.
template <class T>
struct ImplicitRay {
    Vec3<T> inv_dir;  ///< 1 / ray.dir per component (+-inf for a zero component)

    /// Set up for one ray.
    static ImplicitRay make(const Ray<T>& ray) {
        return {Vec3<T>(T(1) / ray.dir.x, T(1) / ray.dir.y, T(1) / ray.dir.z)};
    }
};

/// The window [t0, t1] of the ray inside box, intersected with [tmin, tmax]; false when empty.
/// Slab values are widened by 4 ulps (relative) so rounding never cuts the box; a zero direction
/// component gives +-inf (or NaN, which the comparisons ignore) as the slab tests expect.
template <class T>
bool clip_to_box(const Bounds3<T>& box, const Ray<T>& ray, const ImplicitRay<T>& rd, T& t0, T& t1) {
    T lo = -std::numeric_limits<T>::infinity(), hi = std::numeric_limits<T>::infinity();
    for (std::size_t k = 0; k < 3; ++k) {
        const T inv = rd.inv_dir[k];
        T tn = (box.lo[k] - ray.org[k]) * inv;
        T tf = (box.hi[k] - ray.org[k]) * inv;
        if (tn > tf) {
            std::swap(tn, tf);
        }
        lo = tn > lo ? tn : lo;
        hi = tf < hi ? tf : hi;
    }
    if (ray.dir.x == T(0) || ray.dir.y == T(0) || ray.dir.z == T(0)) {
        // A parallel slab the origin lies outside of gives an empty range through +-inf above,
        // but an origin exactly on a face gives NaN: test containment directly.
        for (std::size_t k = 0; k < 3; ++k) {
            if (ray.dir[k] == T(0) && (ray.org[k] < box.lo[k] || ray.org[k] > box.hi[k])) {
                return false;
            }
        }
    }
    const T pad = T(4) * std::numeric_limits<T>::epsilon();
    lo -= std::abs(lo) * pad;
    hi += std::abs(hi) * pad;
    t0 = std::max(lo, ray.tmin);
    t1 = std::min(hi, ray.tmax);
    return t0 <= t1;
}

/// Same as clip_to_box(box, ray, ImplicitRay<T>::make(ray), t0, t1).
template <class T>
bool clip_to_box(const Bounds3<T>& box, const Ray<T>& ray, T& t0, T& t1) {
    return clip_to_box(box, ray, ImplicitRay<T>::make(ray), t0, t1);
}

/// The hit of the first root u in [0, 1] that first_root(poly) finds, where poly is the surface
/// polynomial along the clipped window (u = 0 at t0, u = 1 at t1).
template <class S, class FirstRoot>
std::optional<PrimHit<typename S::Scalar>> implicit_intersect(
    const PreparedImplicit<S>& p,
    const Ray<typename S::Scalar>& ray,
    const ImplicitRay<typename S::Scalar>& rd,
    FirstRoot&& first_root) {
    using T = typename S::Scalar;
    T t0, t1;
    if (!clip_to_box(p.box, ray, rd, t0, t1) || !std::isfinite(t0) || !std::isfinite(t1)) {
        return std::nullopt;
    }
    const T len = t1 - t0;
    const Polynomial<T, S::degree> poly = p.surface.along(ray.at(t0), ray.dir * len);
    const std::optional<T> u = first_root(poly);
    if (!u) {
        return std::nullopt;
    }
    return PrimHit<T>{std::clamp(t0 + *u * len, t0, t1)};
}

/// Same as implicit_intersect(p, ray, ImplicitRay::make(ray), first_root).
template <class S, class FirstRoot>
std::optional<PrimHit<typename S::Scalar>> implicit_intersect(const PreparedImplicit<S>& p,
                                                              const Ray<typename S::Scalar>& ray,
                                                              FirstRoot&& first_root) {
    return implicit_intersect(p, ray, ImplicitRay<typename S::Scalar>::make(ray),
                              std::forward<FirstRoot>(first_root));
}

/// Unit surface normal (normalised gradient) at a point on the surface.
template <class S>
Vec3<typename S::Scalar> implicit_normal(const PreparedImplicit<S>& p,
                                         const Vec3<typename S::Scalar>& point) {
    return normalize(p.surface.gradient(point));
}

}  // namespace rtlab
