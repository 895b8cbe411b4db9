#pragma once
// Segura & Feito 2001, "Algorithms to test ray-triangle intersection. Comparative study": signs
// of signed volumes only, no hit point; window ends org + tmin dir, org + tmax dir (ray variant if
// infinite); edge volumes from the edge vector (see occludes). Epsilon: none (zero volume =
// touching; n.dir == 0 misses). Cost: 3 cross, 6 dot (the edges' order is fixed once). No per-ray
// set-up: the window ends depend on [tmin, tmax], which a closest-hit traversal shrinks.

#include "intersect/lanes.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstddef>
#include <string_view>

namespace rtlab {

/// Segura–Feito hit/no-hit ray/triangle test (OcclusionMethod only), templated on the scalar;
/// for float also on lane_count triangles at once (LaneOcclusionMethod, intersect/lanes.h).
template <class T>
struct SeguraFeito {
    using Scalar = T;
    using Shape = Triangle<T>;

    /// The plane (unnormalised normal n = (p1 - p0) x (p2 - p0), zero when degenerate, through p0)
    /// and each edge (p0 p1, p1 p2, p2 p0) with its endpoints in lexicographic order: from the
    /// first, `along` the second minus the first, `sign` -1 where that order reverses the edge
    /// (see occludes); in scalars S and vectors Vec (one triangle) or lanes (lane_count).
    template <class S, class Vec>
    struct Form {
        Vec n, p0;
        Vec from[3], along[3];
        S sign[3];
    };
    /// One triangle's form and its box.
    struct Prepared : Form<T, Vec3<T>> {
        Bounds3<T> box;
    };
    /// lane_count triangles' forms, lane k holding one (set_lane).
    using Lanes = Form<FloatLanes, Vec3Lanes>;

    static constexpr std::string_view name = "segura_feito";

    /// The plane and the ordered edges (n zero for a zero-area triangle: never hits).
    static Prepared prepare(const Shape& s) {
        Prepared p{};
        p.box = triangle_bounds(s.p0, s.p1, s.p2);
        p.p0 = s.p0;
        if (!is_degenerate(s.p0, s.p1, s.p2)) {
            p.n = cross(s.p1 - s.p0, s.p2 - s.p0);
        }
        const Vec3<T>* v[3] = {&s.p0, &s.p1, &s.p2};
        for (std::size_t e = 0; e < 3; ++e) {
            const Vec3<T>& pi = *v[e];
            const Vec3<T>& pj = *v[(e + 1) % 3];
            const bool ordered =
                pi.x < pj.x || (pi.x == pj.x && (pi.y < pj.y || (pi.y == pj.y && pi.z <= pj.z)));
            p.from[e] = ordered ? pi : pj;
            p.along[e] = ordered ? pj - pi : pi - pj;
            p.sign[e] = ordered ? T(1) : T(-1);
        }
        return p;
    }

    /// Box around the three vertices.
    static Bounds3<T> bounds(const Prepared& p) { return p.box; }

    /// True when the ray meets the triangle at some t in [ray.tmin, ray.tmax].
    static bool occluded(const Prepared& p, const Ray<T>& ray) { return occludes<T>(p, ray); }

    /// The test on one triangle (L = T, P = Prepared) or on lanes (L = FloatLanes, P = Lanes).
    /// Each edge's signed volume dir . ((pi - a) x (pj - a)) of the tetrahedron (a, a + dir, pi,
    /// pj) is evaluated as sign dir . ((from - a) x along). Why: the short edge vector keeps the
    /// error at ~eps D / s for a triangle of size s at distance D from a, where the textbook
    /// (pi - a) x (pj - a) cancels to ~eps (D / s)^2 (wrong answers from D / s ~ 1e4 in float,
    /// 1e7 in double: stability case far_small); the fixed endpoint order makes the two triangles
    /// of a shared edge compute exactly opposite values, so the test stays watertight across
    /// shared edges.
    template <class L, class P>
    static MaskOf<L> occludes(const P& p, const Ray<T>& ray) {
        // A ray parallel to the plane (or in it), or a degenerate triangle (n = 0): miss.
        const auto dir = splat3<L>(ray.dir);
        const L n_dir = dot(p.n, dir);
        MaskOf<L> ok = n_dir != T(0);
        if (none(ok)) {
            return ok;
        }
        // Window ends: signed volume of each end against the triangle's plane.
        const Vec3<T> a = ray.org + ray.dir * ray.tmin;
        const auto a_lanes = splat3<L>(a);
        const L side_a = dot(p.n, a_lanes - p.p0);
        const Vec3<T> b = ray.org + ray.dir * ray.tmax;
        const L side_b = is_finite(b) ? dot(p.n, splat3<L>(b) - p.p0) : n_dir;
        // Not both ends strictly on one side (nor NaN).
        ok = ok & (((side_a <= T(0)) & (side_b >= T(0))) | ((side_a >= T(0)) & (side_b <= T(0))));
        if (none(ok)) {
            return ok;
        }
        // Line test: the tetrahedra (a, a + dir, pi, pj) for the three edges share one sign.
        L vol[3];
        for (std::size_t e = 0; e < 3; ++e) {
            vol[e] = p.sign[e] * dot(dir, cross(p.from[e] - a_lanes, p.along[e]));
        }
        const MaskOf<L> any_neg = (vol[0] < T(0)) | (vol[1] < T(0)) | (vol[2] < T(0));
        const MaskOf<L> any_pos = (vol[0] > T(0)) | (vol[1] > T(0)) | (vol[2] > T(0));
        return ok & (any_neg != any_pos);  // all >= 0 or all <= 0, and not all zero
    }

    /// Stores p in lane k of g (a float method only).
    static void set_lane(Lanes& g, unsigned k, const Prepared& p) {
        rtlab::set_lane(g.n, k, p.n);
        rtlab::set_lane(g.p0, k, p.p0);
        for (std::size_t e = 0; e < 3; ++e) {
            rtlab::set_lane(g.from[e], k, p.from[e]);
            rtlab::set_lane(g.along[e], k, p.along[e]);
            g.sign[e][k] = p.sign[e];
        }
    }
};

static_assert(OcclusionMethod<SeguraFeito<float>>);
static_assert(OcclusionMethod<SeguraFeito<double>>);
static_assert(LaneOcclusionMethod<SeguraFeito<float>>);

}  // namespace rtlab
