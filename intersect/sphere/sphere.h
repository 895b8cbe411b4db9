#pragma once
// Sphere: the shape every sphere intersection method prepares, plus the helpers they share.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/lanes.h"
#include "intersect/method.h"
#include "intersect/ray.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace rtlab {

/// A sphere of the given centre and radius (radius > 0).
template <class T>
struct Sphere {
    Vec3<T> center;
    T radius = 1;
};

using Spheref = Sphere<float>;
using Sphered = Sphere<double>;

/// What every sphere method prepares: the centre and the radius with its square.
template <class T>
struct PreparedSphere {
    Vec3<T> center;
    T radius = 1;
    T radius2 = 1;
};

/// The per-ray set-up of the sphere methods: a = dir . dir, the quadratic's leading coefficient.
template <class T>
struct SphereRay {
    T a = 1;  ///< dot(ray.dir, ray.dir)

    /// Set up for one ray.
    static SphereRay make(const Ray<T>& ray) { return {dot(ray.dir, ray.dir)}; }
};

namespace detail {

/// Prepared form shared by the sphere methods.
template <class T>
PreparedSphere<T> prepare_sphere(const Sphere<T>& s) {
    return {s.center, s.radius, s.radius * s.radius};
}

/// Box around the sphere, each bound moved one ulp outwards so rounding of centre +- radius can
/// never cut the sphere.
template <class T>
Bounds3<T> sphere_bounds(const PreparedSphere<T>& p) {
    constexpr T inf = std::numeric_limits<T>::infinity();
    Bounds3<T> b;
    for (std::size_t k = 0; k < 3; ++k) {
        b.lo[k] = std::nextafter(p.center[k] - p.radius, -inf);
        b.hi[k] = std::nextafter(p.center[k] + p.radius, inf);
    }
    return b;
}

}  // namespace detail

/// The two sorted roots of a line and a sphere, on one sphere (L = T) or on lanes: `ok` where the
/// line meets it (the roots may still be NaN there, as the scalar formulas give them).
template <class L>
struct SphereRoots {
    MaskOf<L> ok{};
    L near{}, far{};
};

/// The hit of sorted roots r on one sphere or on lanes: the nearer root when it lies in [tmin,
/// tmax], else the farther one when it does (the leaving root, origin inside the sphere).
template <class L, class T>
LaneHit<L> pick_root(const SphereRoots<L>& r, const Ray<T>& ray) {
    LaneHit<L> h;
    const MaskOf<L> in_near = (r.near >= ray.tmin) & (r.near <= ray.tmax);
    const MaskOf<L> in_far = (r.far >= ray.tmin) & (r.far <= ray.tmax);
    h.hit = r.ok & (in_near | in_far);
    h.t = in_near ? r.near : r.far;
    return h;
}

namespace detail {

/// pick_root of a scalar roots function's answer.
template <class T>
std::optional<PrimHit<T>> pick_root(const std::optional<std::pair<T, T>>& roots,
                                    const Ray<T>& ray) {
    if (!roots) {
        return std::nullopt;
    }
    const LaneHit<T> h = rtlab::pick_root(SphereRoots<T>{true, roots->first, roots->second}, ray);
    return h.hit ? std::optional(PrimHit<T>{h.t}) : std::nullopt;
}

}  // namespace detail

/// The lane form of sphere methods written once over their scalar (intersect/lanes.h): lanes of
/// prepared spheres.
template <class T>
struct SphereLaneForm {
    /// lane_count prepared spheres, lane k holding one.
    struct Lanes {
        Vec3Lanes center;
        FloatLanes radius{}, radius2{};
    };
    /// Stores p in lane k of g.
    static void set_lane(Lanes& g, unsigned k, const PreparedSphere<T>& p) {
        rtlab::set_lane(g.center, k, p.center);
        g.radius[k] = p.radius;
        g.radius2[k] = p.radius2;
    }
    /// The scalar roots of a lane-form roots function's answer for one sphere.
    static std::optional<std::pair<T, T>> scalar(const SphereRoots<T>& r) {
        return r.ok ? std::optional(std::pair<T, T>{r.near, r.far}) : std::nullopt;
    }
};

/// What every sphere method shares (derive from it, CRTP): the family's types, prepare_sphere,
/// sphere_bounds, the per-ray set-up a = dir . dir (SphereRay), and intersect as the nearest root
/// of Self::roots(p, ray, rd) in the window. A method adds its name and roots, and writes its own
/// intersect for an early out.
template <class Self, class T>
struct SphereMethodBase : FamilyRayMethod<Self,
                                          T,
                                          Sphere<T>,
                                          PreparedSphere<T>,
                                          detail::prepare_sphere<T>,
                                          detail::sphere_bounds<T>,
                                          SphereRay<T>> {
    using MethodDefaults<Self>::intersect;

    /// Nearest t in [tmin, tmax]; the leaving root when the origin is inside.
    static std::optional<PrimHit<T>> intersect(const PreparedSphere<T>& p,
                                               const Ray<T>& ray,
                                               const SphereRay<T>& rd) {
        return detail::pick_root(Self::roots(p, ray, rd), ray);
    }
};

/// Unit outward normal of a sphere at a point on (or near) its surface.
template <class T>
Vec3<T> sphere_normal(const PreparedSphere<T>& p, const Vec3<T>& point) {
    return normalize(point - p.center);
}

}  // namespace rtlab
