#pragma once
// Truncated cone (NFF `c` record): the lateral surface between a base disk and an apex disk, both
// perpendicular to the axis; a cylinder when the radii are equal, a pointed cone when one radius
// is 0. Open-ended as in NFF unless caps are asked for. Shared by every cone method.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace rtlab {

/// Which end disks of a cone are part of its surface (NFF cones have none).
enum class ConeCaps : std::uint8_t { none = 0, base = 1, apex = 2, both = 3 };

/// True when caps include the end `end` (ConeCaps::base or ConeCaps::apex).
constexpr bool has_cap(ConeCaps caps, ConeCaps end) {
    return (static_cast<unsigned>(caps) & static_cast<unsigned>(end)) != 0;
}

/// A truncated cone from the base disk (centre `base`, radius base_radius) to the apex disk
/// (centre `apex`, radius apex_radius). Valid: base != apex, radii >= 0, not both 0.
template <class T>
struct Cone {
    Vec3<T> base;
    T base_radius = 1;
    Vec3<T> apex{0, 0, 1};
    T apex_radius = 1;
    ConeCaps caps = ConeCaps::none;
};

using Conef = Cone<float>;
using Coned = Cone<double>;

/// What every cone method prepares: the cone, its unit axis and height, the radius slope, an
/// orthonormal frame (e1, e2, axis) and the axis midpoint with its radius.
template <class T>
struct PreparedCone {
    Vec3<T> base;
    Vec3<T> apex;
    Vec3<T> axis;  ///< unit, base -> apex
    Vec3<T> e1;    ///< unit, perpendicular to axis
    Vec3<T> e2;    ///< unit, cross(axis, e1)
    Vec3<T> mid;   ///< (base + apex) / 2
    T height = 1;  ///< |apex - base|
    T r0 = 1;      ///< base radius
    T r1 = 1;      ///< apex radius
    T rm = 1;      ///< radius at mid, (r0 + r1) / 2
    T slope = 0;   ///< k = (r1 - r0) / height: radius grows by k per unit along the axis
    ConeCaps caps = ConeCaps::none;
};

/// The per-ray set-up of the world-space cone methods: dd = dir . dir.
template <class T>
struct ConeRay {
    T dd = 1;  ///< dot(ray.dir, ray.dir)

    /// Set up for one ray.
    static ConeRay make(const Ray<T>& ray) { return {dot(ray.dir, ray.dir)}; }
};

namespace detail {

/// Two unit vectors completing unit n to a right-handed orthonormal frame (Duff et al.,
/// "Building an Orthonormal Basis, Revisited", JCGT 2017).
template <class T>
void orthonormal_frame(const Vec3<T>& n, Vec3<T>& b1, Vec3<T>& b2) {
    const T sign = std::copysign(T(1), n.z);
    const T a = T(-1) / (sign + n.z);
    const T b = n.x * n.y * a;
    b1 = {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
    b2 = {b, sign + n.y * n.y * a, -n.y};
}

/// Prepared form shared by the cone methods.
template <class T>
PreparedCone<T> prepare_cone(const Cone<T>& c) {
    PreparedCone<T> p;
    p.base = c.base;
    p.apex = c.apex;
    const Vec3<T> e = c.apex - c.base;
    p.height = std::sqrt(dot(e, e));
    p.axis = e / p.height;
    orthonormal_frame(p.axis, p.e1, p.e2);
    p.mid = (c.base + c.apex) * T(0.5);
    p.r0 = c.base_radius;
    p.r1 = c.apex_radius;
    p.rm = (c.base_radius + c.apex_radius) * T(0.5);
    p.slope = (c.apex_radius - c.base_radius) / p.height;
    p.caps = c.caps;
    return p;
}

/// Conservative box of a truncated cone: per axis k, each end disk spans its centre +- r sin(a_k)
/// (a_k the angle between the cone axis and axis k, sin from the two other axis components, so
/// axis-aligned cones get exact boxes); padded for rounding.
template <class T>
Bounds3<T> cone_bounds(const Vec3<T>& base, T r0, const Vec3<T>& apex, T r1) {
    constexpr T inf = std::numeric_limits<T>::infinity();
    constexpr T eps = std::numeric_limits<T>::epsilon();
    const Vec3<T> e = apex - base;
    const T len2 = dot(e, e);
    Bounds3<T> b;
    for (std::size_t k = 0; k < 3; ++k) {
        const T a = e[(k + 1) % 3], c = e[(k + 2) % 3];
        const T s = std::min(T(1), std::sqrt((a * a + c * c) / len2) * (T(1) + 8 * eps));
        const T x0 = r0 * s, x1 = r1 * s;
        // Absolute slack for the rounding of centre +- extent (and of e and s above).
        const T slack =
            4 * eps * (std::max(std::abs(base[k]), std::abs(apex[k])) + std::max(r0, r1));
        b.lo[k] = std::nextafter(std::min(base[k] - x0, apex[k] - x1) - slack, -inf);
        b.hi[k] = std::nextafter(std::max(base[k] + x0, apex[k] + x1) + slack, inf);
    }
    return b;
}

/// Box of a prepared cone.
template <class T>
Bounds3<T> cone_bounds(const PreparedCone<T>& p) {
    return cone_bounds(p.base, p.r0, p.apex, p.r1);
}

/// Keeps the nearer of `best` and t when t lies in [tmin, tmax]; u and v as in cone hits
/// (u: 0 lateral surface, 1 base cap, 2 apex cap; v: position along the axis, 0 base, 1 apex).
template <class T>
void keep_nearest(std::optional<PrimHit<T>>& best, T t, T u, T v, const Ray<T>& ray) {
    if (t >= ray.tmin && t <= ray.tmax && (!best || t < best->t)) {
        best = PrimHit<T>{t, u, v};
    }
}

/// The cap hits of a ray in the cone's terms: s0 = (org - base) . axis and sd = dir . axis; the
/// caps' planes are s = 0 and s = height, and a plane point counts when within the end's radius.
template <class T>
void cap_hits(
    const PreparedCone<T>& p, const Ray<T>& ray, T s0, T sd, std::optional<PrimHit<T>>& best) {
    if (p.caps == ConeCaps::none || sd == T(0)) {
        return;
    }
    if (has_cap(p.caps, ConeCaps::base)) {
        const T t = -s0 / sd;
        const Vec3<T> q = ray.at(t) - p.base;
        if (dot(q, q) <= p.r0 * p.r0) {
            keep_nearest(best, t, T(1), T(0), ray);
        }
    }
    if (has_cap(p.caps, ConeCaps::apex)) {
        const T t = (p.height - s0) / sd;
        const Vec3<T> q = ray.at(t) - p.apex;
        if (dot(q, q) <= p.r1 * p.r1) {
            keep_nearest(best, t, T(2), T(1), ray);
        }
    }
}

}  // namespace detail

/// What every world-space cone method shares (derive from it, CRTP): the family's types,
/// prepare_cone, cone_bounds and the per-ray set-up dd = dir . dir (ConeRay). A method adds its
/// name and the three-argument intersect (with `using ConeMethodBase<Self, T>::intersect;` for
/// the other forms).
template <class Self, class T>
using ConeMethodBase =
    FamilyRayMethod<Self,
                    T,
                    Cone<T>,
                    PreparedCone<T>,
                    detail::prepare_cone<T>,
                    static_cast<Bounds3<T> (*)(const PreparedCone<T>&)>(detail::cone_bounds<T>),
                    ConeRay<T>>;

/// Unnormalised outward normal of the lateral surface at p (on or near it): the radial direction
/// tilted against the axis by the slope. Caps are not considered.
template <class T>
Vec3<T> cone_side_normal(const PreparedCone<T>& p, const Vec3<T>& point) {
    const Vec3<T> w = point - p.base;
    const Vec3<T> radial = w - p.axis * dot(w, p.axis);
    const T len = std::sqrt(dot(radial, radial));
    if (!(len > 0)) {
        return p.slope <= 0 ? p.axis : -p.axis;  // the tip of a pointed cone
    }
    return radial / len - p.axis * p.slope;
}

/// Unnormalised outward normal at p: the side's, or a cap's (-axis at the base, +axis at the
/// apex) when p is closer to that cap's plane than to the lateral surface.
template <class T>
Vec3<T> cone_normal(const PreparedCone<T>& p, const Vec3<T>& point) {
    const Vec3<T> w = point - p.base;
    const T s = dot(w, p.axis);
    const Vec3<T> radial = w - p.axis * s;
    const T rho = std::sqrt(dot(radial, radial));
    // Distance to the lateral surface: |rho - r(s)| cos(half angle).
    const T side = std::abs(rho - (p.r0 + p.slope * s)) / std::sqrt(T(1) + p.slope * p.slope);
    if (has_cap(p.caps, ConeCaps::base) && std::abs(s) < side) {
        return -p.axis;
    }
    if (has_cap(p.caps, ConeCaps::apex) && std::abs(s - p.height) < side) {
        return p.axis;
    }
    return cone_side_normal(p, point);
}

}  // namespace rtlab
