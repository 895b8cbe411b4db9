#pragma once
// Planar polygons (convex or concave, n >= 3) and the preparation shared by the polygon methods:
// the plane by Newell's method (Sutherland, Sproull & Schumacker 1974; Tampieri, Graphics Gems
// III) and the 2D projection that drops the normal's dominant axis (seed 000, "Schnitt
// Strahl-Polygon"). Cost of the plane step per ray: 2 dot products, 1 div.

#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace rtlab {

/// A planar polygon given by its vertices in order (either orientation), n >= 3; it may be
/// concave. Vertices that are not exactly coplanar are judged on the plane of PreparedPolygon.
template <class T>
struct Polygon {
    std::vector<Vec3<T>> vertices;
};

/// The polygon's plane and its projection on the coordinate plane that drops the normal's
/// dominant axis.
template <class T>
struct PreparedPolygon {
    Vec3<T> normal;  ///< Newell normal (not normalised); zero when degenerate
    Vec3<T> origin;  ///< the first vertex: the plane is dot(normal, p - origin) = 0
    std::size_t axis_u = 0, axis_v = 1;  ///< kept axes of the projection
    std::vector<std::array<T, 2>> pts;   ///< projected vertices (p[axis_u], p[axis_v])
    Bounds3<T> box;                      ///< bounds of the vertices
};

namespace detail {

/// Newell's normal in the translation-invariant form sum_i (v_i - v_0) x (v_{i+1} - v_0), which
/// equals the classical sum of (y_i - y_j)(z_i + z_j) terms in exact arithmetic but loses less to
/// cancellation far from the origin; it is twice the vector area, exact for planar polygons.
template <class T>
Vec3<T> newell_normal(const std::vector<Vec3<T>>& v) {
    Vec3<T> n;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
        n += cross(v[i] - v[0], v[i + 1] - v[0]);
    }
    return n;
}

/// Plane, dominant axis and projected vertices of a polygon.
template <class T>
PreparedPolygon<T> prepare_polygon(const Polygon<T>& poly) {
    PreparedPolygon<T> p;
    for (const Vec3<T>& v : poly.vertices) {
        p.box.extend(v);
    }
    if (poly.vertices.size() < 3) {
        return p;  // zero normal: every ray misses
    }
    p.normal = newell_normal(poly.vertices);
    p.origin = poly.vertices[0];
    const std::size_t drop = max_abs_axis(p.normal);
    p.axis_u = (drop + 1) % 3;
    p.axis_v = (drop + 2) % 3;
    p.pts.reserve(poly.vertices.size());
    for (const Vec3<T>& v : poly.vertices) {
        p.pts.push_back({v[p.axis_u], v[p.axis_v]});
    }
    return p;
}

/// The box of the polygon's vertices.
template <class T>
Bounds3<T> polygon_box(const PreparedPolygon<T>& p) {
    return p.box;
}

/// Where the ray meets the polygon's plane inside [tmin, tmax]: t and the projected point.
template <class T>
struct PlaneHit {
    T t;
    T pu, pv;
};

/// Ray-plane step: nullopt when the ray is parallel to the plane (dot(n, d) == 0, no epsilon),
/// when t is outside [tmin, tmax], or when t overflows to infinity.
template <class T>
std::optional<PlaneHit<T>> polygon_plane_hit(const PreparedPolygon<T>& p, const Ray<T>& ray) {
    const T denom = dot(p.normal, ray.dir);
    if (denom == T(0)) {
        return std::nullopt;
    }
    const T t = dot(p.normal, p.origin - ray.org) / denom;
    if (!(t >= ray.tmin && t <= ray.tmax) || std::isinf(t)) {
        return std::nullopt;
    }
    return PlaneHit<T>{t, ray.org[p.axis_u] + t * ray.dir[p.axis_u],
                       ray.org[p.axis_v] + t * ray.dir[p.axis_v]};
}

/// Twice the signed area of (origin, a, b) with the point at the origin: > 0 when the edge a->b
/// passes the point counter-clockwise. The same rounded value for (a, b) and, negated, for (b, a),
/// so an edge shared by two polygons is judged consistently.
template <class T>
T edge_side(T au, T av, T bu, T bv) {
    return au * bv - av * bu;
}

}  // namespace detail

/// What every polygon method shares (derive from it, CRTP): the types, prepare, bounds and
/// intersect as the plane step (detail::polygon_plane_hit) then Self::contains(p, pu, pv), the
/// method's point-in-polygon test of the projected hit point. A method adds its name and contains.
template <class Self, class T>
struct PolygonMethodBase : FamilyMethod<Self,
                                        T,
                                        Polygon<T>,
                                        PreparedPolygon<T>,
                                        detail::prepare_polygon<T>,
                                        detail::polygon_box<T>> {
    /// Nearest (the only) hit in [tmin, tmax]; u = v = 0.
    static std::optional<PrimHit<T>> intersect(const PreparedPolygon<T>& p, const Ray<T>& ray) {
        const auto h = detail::polygon_plane_hit(p, ray);
        if (!h || !Self::contains(p, h->pu, h->pv)) {
            return std::nullopt;
        }
        return PrimHit<T>{h->t, T(0), T(0)};
    }
};

}  // namespace rtlab
