#pragma once
// Badouel 1990, "An efficient ray-polygon intersection" (Graphics Gems): ray-plane t, then 2D
// barycentrics in the plane that drops the dominant normal axis (plane and inverse 2x2 map
// precomputed). Epsilon: none (n.dir == 0 misses, edges inclusive). Cost: 2 dot, 1 div, 6 madd.

#include "intersect/hit.h"
#include "intersect/lanes.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace rtlab {

/// Badouel's plane-then-projection ray/triangle test, templated on the scalar type.
template <class T>
struct Badouel : MethodDefaults<Badouel<T>> {
    using Scalar = T;
    using Shape = Triangle<T>;

    /// Plane n.x = d (n unnormalised, zero for a degenerate triangle), p0 projected onto the
    /// kept axes i1, i2, and the rows of the inverse 2x2 map from projected offsets to (u, v); in
    /// scalars S with axis indices I (one triangle), or in lanes (lane_count triangles).
    template <class S, class Vec, class I>
    struct Form {
        Vec n;
        S d;
        S p0_i1, p0_i2;
        S u_i1, u_i2;  ///< u = u_i1 * (x[i1] - p0[i1]) + u_i2 * (x[i2] - p0[i2])
        S v_i1, v_i2;  ///< v = v_i1 * (x[i1] - p0[i1]) + v_i2 * (x[i2] - p0[i2])
        I i1, i2;
    };
    /// One triangle's form and its box.
    struct Prepared : Form<T, Vec3<T>, std::uint8_t> {
        Bounds3<T> box;
    };
    /// lane_count triangles' forms, lane k holding one (set_lane).
    using Lanes = Form<FloatLanes, Vec3Lanes, MaskLanes>;

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
        const LaneHit<T> h = test<T>(p, ray);
        return h.hit ? std::optional(PrimHit<T>{h.t, h.u, h.v}) : std::nullopt;
    }

    /// The test on one triangle (L = T, P = Prepared) or on lanes (L = FloatLanes, P = Lanes).
    template <class L, class P>
    static LaneHit<L> test(const P& p, const Ray<T>& ray) {
        LaneHit<L> h;
        const auto org = splat3<L>(ray.org);
        const auto dir = splat3<L>(ray.dir);
        // Ray-plane distance.
        const L ndir = dot(p.n, dir);
        MaskOf<L> ok = ndir != T(0);
        if (none(ok)) {
            return h;
        }
        const L t = (p.d - dot(p.n, org)) / ndir;
        ok = ok & (t >= ray.tmin) & (t <= ray.tmax) & (t <= std::numeric_limits<T>::max());
        if (none(ok)) {
            return h;
        }
        // 2D barycentrics of the projected hit point.
        const L a = pick(org, p.i1) + t * pick(dir, p.i1) - p.p0_i1;
        const L b = pick(org, p.i2) + t * pick(dir, p.i2) - p.p0_i2;
        const L u = p.u_i1 * a + p.u_i2 * b;
        ok = ok & (u >= T(0)) & (u <= T(1));
        if (none(ok)) {
            return h;
        }
        const L v = p.v_i1 * a + p.v_i2 * b;
        h.hit = ok & (v >= T(0)) & (u + v <= T(1));
        h.t = t;
        h.u = u;
        h.v = v;
        return h;
    }

    /// Stores p in lane k of g (a float method only).
    static void set_lane(Lanes& g, unsigned k, const Prepared& p) {
        rtlab::set_lane(g.n, k, p.n);
        g.d[k] = p.d;
        g.p0_i1[k] = p.p0_i1;
        g.p0_i2[k] = p.p0_i2;
        g.u_i1[k] = p.u_i1;
        g.u_i2[k] = p.u_i2;
        g.v_i1[k] = p.v_i1;
        g.v_i2[k] = p.v_i2;
        g.i1[k] = p.i1;
        g.i2[k] = p.i2;
    }
};

static_assert(IntersectionMethod<Badouel<float>>);
static_assert(IntersectionMethod<Badouel<double>>);

}  // namespace rtlab
