#pragma once
// Badouel 1990, "An efficient ray-polygon intersection" (Graphics Gems): ray-plane t, then 2D
// barycentrics in the plane that drops the dominant normal axis (plane and inverse 2x2 map
// precomputed). Epsilon: none (n.dir == 0 misses, edges inclusive). Cost: 2 dot, 1 div, 6 madd.

#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstdint>
#include <optional>
#include <string_view>

namespace rtlab {

/// Badouel's plane-then-projection ray/triangle test, templated on the scalar type.
template <class T>
struct Badouel : MethodDefaults<Badouel<T>> {
    using Scalar = T;
    using Shape = Triangle<T>;

    /// Plane n.x = d (n unnormalised, zero for a degenerate triangle), p0 projected onto the
    /// kept axes i1, i2, and the rows of the inverse 2x2 map from projected offsets to (u, v).
    struct Prepared {
        Vec3<T> n;
        T d;
        T p0_i1, p0_i2;
        T u_i1, u_i2;  ///< u = u_i1 * (x[i1] - p0[i1]) + u_i2 * (x[i2] - p0[i2])
        T v_i1, v_i2;  ///< v = v_i1 * (x[i1] - p0[i1]) + v_i2 * (x[i2] - p0[i2])
        std::uint8_t i1, i2;
        Bounds3<T> box;
    };

    static constexpr std::string_view name = "badouel";

    /// Precompute the plane and the projection that drops the dominant normal axis.
    static Prepared prepare(const Shape& s) {
        Prepared p{};
        p.box = triangle_bounds(s.p0, s.p1, s.p2);
        const Vec3<T> e1 = s.p1 - s.p0;
        const Vec3<T> e2 = s.p2 - s.p0;
        const Vec3<T> n = cross(e1, e2);
        const std::size_t k = max_abs_axis(n);
        const std::size_t i1 = (k + 1) % 3;
        const std::size_t i2 = (k + 2) % 3;
        p.i1 = static_cast<std::uint8_t>(i1);
        p.i2 = static_cast<std::uint8_t>(i2);
        // The 2x2 determinant e1[i1] e2[i2] - e2[i1] e1[i2] is n[k], the largest normal component.
        const T det = n[k];
        if (det == T(0) || is_degenerate(s.p0, s.p1, s.p2)) {
            return p;  // n = 0 stays zero: never hits
        }
        p.n = n;
        p.d = dot(n, s.p0);
        p.p0_i1 = s.p0[i1];
        p.p0_i2 = s.p0[i2];
        const T inv = T(1) / det;
        p.u_i1 = e2[i2] * inv;
        p.u_i2 = -e2[i1] * inv;
        p.v_i1 = -e1[i2] * inv;
        p.v_i2 = e1[i1] * inv;
        return p;
    }

    /// Box around the three vertices.
    static Bounds3<T> bounds(const Prepared& p) { return p.box; }

    /// Hit with t in [ray.tmin, ray.tmax] and barycentrics u (p1), v (p2), or nullopt.
    static std::optional<PrimHit<T>> intersect(const Prepared& p, const Ray<T>& ray) {
        // Ray-plane distance.
        const T ndir = dot(p.n, ray.dir);
        if (ndir == T(0)) {
            return std::nullopt;
        }
        const T t = (p.d - dot(p.n, ray.org)) / ndir;
        if (!in_window(t, ray)) {
            return std::nullopt;
        }
        // 2D barycentrics of the projected hit point.
        const T a = ray.org[p.i1] + t * ray.dir[p.i1] - p.p0_i1;
        const T b = ray.org[p.i2] + t * ray.dir[p.i2] - p.p0_i2;
        const T u = p.u_i1 * a + p.u_i2 * b;
        if (!(u >= T(0) && u <= T(1))) {
            return std::nullopt;
        }
        const T v = p.v_i1 * a + p.v_i2 * b;
        if (!(v >= T(0) && u + v <= T(1))) {
            return std::nullopt;
        }
        return PrimHit<T>{t, u, v};
    }
};

static_assert(IntersectionMethod<Badouel<float>>);
static_assert(IntersectionMethod<Badouel<double>>);

}  // namespace rtlab
