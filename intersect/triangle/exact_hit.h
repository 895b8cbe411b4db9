#pragma once
// Certified ray/triangle hits: a filtered predicate. A double evaluation of the watertight test's
// edge functions (Woop, Benthin & Wald 2013) in unsheared form, with static forward error bounds
// (Higham 2002, §3.1), decides every ray whose signs are certain; the rest are redone in exact
// rational arithmetic (GMP, exact_hit.cpp). Cost: about 60 double flops per test when filtered.
//
// Semantics, with org, dir, tmin, tmax and the vertices taken as the exact reals the floats hold:
// - the ray is the set {org + t * dir : tmin <= t <= tmax}; an infinite tmin or tmax leaves that
//   side open (tmin = +inf or tmax = -inf: empty);
// - the triangle is closed: its edges and vertices belong to it;
// - a triangle with zero area, or a ray whose line is parallel to the triangle's plane (including a
//   ray lying in that plane), is a miss;
// - a hit reports t rounded to the nearest float (ties to even) from the exact t, and barycentrics
//   u (weight of p1) and v (weight of p2) close to nearest.
// Preconditions: finite vertices, a finite origin and direction, tmin and tmax not NaN.

#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"
#include "intersect/vec.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace rtlab {

/// The certified outcome of one ray/triangle test.
struct ExactHit {
    float t = std::numeric_limits<float>::infinity();  ///< nearest float to the exact t (hits)
    float u = 0;                                       ///< barycentric weight of p1 (hits)
    float v = 0;                                       ///< barycentric weight of p2 (hits)
    bool hit = false;                                  ///< the exact decision
    bool fallback = false;  ///< exact arithmetic was needed to decide or round
};

namespace exact_detail {

/// Signed integer decision of an exact quantity from its double value and error bound: -1, 0 or
/// +1 when certain, 2 when |value| <= bound (0 is certain only with a zero bound, which means every
/// term of the sum was exactly zero).
inline int certain_sign(double value, double bound) {
    if (bound == 0.0) {
        return (value > 0.0) - (value < 0.0);
    }
    if (std::abs(value) <= bound) {
        return 2;
    }
    return value > 0.0 ? 1 : -1;
}

/// Double evaluations of the exact quantities of one ray/triangle pair, and their error bounds.
/// With a = p0 - org, b = p1 - org, c = p2 - org, d = dir (all exact reals):
/// U = d.(b x c), V = d.(c x a), W = d.(a x b) (barycentric weights of p0, p1, p2 times D),
/// D = d.((p1 - p0) x (p2 - p0)) = U + V + W, T = a.(b x c); the exact hit is at t = T / D.
struct Terms {
    double u, v, w, d, t;
    double eu, ev, ew, ed, et;  ///< |computed - exact| <= bound, for each quantity
};

/// d . (b x c) and its absolute-value twin (the "permanent"), products of three doubles.
inline void triple(const Vec3d& d, const Vec3d& b, const Vec3d& c, double& value, double& perm) {
    value = d.x * (b.y * c.z - b.z * c.y) + d.y * (b.z * c.x - b.x * c.z) +
            d.z * (b.x * c.y - b.y * c.x);
    const Vec3d ad = abs(d), ab = abs(b), ac = abs(c);
    perm = ad.x * (ab.y * ac.z + ab.z * ac.y) + ad.y * (ab.z * ac.x + ab.x * ac.z) +
           ad.z * (ab.x * ac.y + ab.y * ac.x);
}

/// Evaluates the five quantities in double with forward error bounds. Each is written with at most
/// one origin-relative factor (b x c = (b - c) x c, and so on), so a far origin does not blow up
/// the bounds: U = d.((p1 - p2) x c), V = d.((p2 - p0) x a), W = d.((p0 - p1) x b),
/// D = d.(e1 x e2), T = a.(e1 x e2) with e1 = p1 - p0, e2 = p2 - p0.
/// Derivation (Higham 2002, "Accuracy and Stability of Numerical Algorithms", §3.1, Lemma 3.1):
/// inputs are floats, exact in double. Each term of d.(x x y) is d_i x_j y_k computed through at
/// most 7 roundings (x_j, y_k as float differences: 2; product, difference, times d_i: 3; the
/// two-level sum: 2), so |computed - exact| <= gamma_7 * sum|terms| (gamma_n = nu / (1 - nu),
/// u = 2^-53). The permanent, computed the same way from |.|, satisfies sum|terms| <=
/// perm / (1 - u)^7, and gamma_7 / (1 - u)^7 < 8u: bound 8u * perm (exact: a power-of-two scaling;
/// no underflow, since every product of three floats is a multiple of 2^-447, nor overflow, as
/// |products| < 2^390). T has the rounded a as a third inexact factor: 8 roundings, 9u * perm.
inline Terms evaluate(const Rayf& ray, const Vec3f& p0, const Vec3f& p1, const Vec3f& p2) {
    constexpr double u = 0x1.0p-53;
    const Vec3d o(ray.org), d(ray.dir), q0(p0), q1(p1), q2(p2);
    const Vec3d a = q0 - o, b = q1 - o, c = q2 - o;
    const Vec3d e1 = q1 - q0, e2 = q2 - q0;
    Terms r{};
    double perm = 0;
    triple(d, q1 - q2, c, r.u, perm);
    r.eu = 8 * u * perm;
    triple(d, e2, a, r.v, perm);
    r.ev = 8 * u * perm;
    triple(d, q0 - q1, b, r.w, perm);
    r.ew = 8 * u * perm;
    triple(d, e1, e2, r.d, perm);
    r.ed = 8 * u * perm;
    triple(a, e1, e2, r.t, perm);
    r.et = 9 * u * perm;
    return r;
}

/// Sign of s * (T - bound * D) for one end of the window (s = sign of D), or 2 when uncertain.
/// Error: |T^ - T| <= et, |D^ - D| <= ed; the product bound * D^ and the difference round once each
/// (|fl(x) - x| <= u |fl(x)|), so the bound is et + |bound| ed + u (|x^| + |bound D^|), inflated by
/// (1 + 2^-48) to cover the rounding of its own evaluation (four operations, < 5u).
inline int window_sign(const Terms& r, int s, float bound) {
    constexpr double u = 0x1.0p-53;
    const double b = static_cast<double>(bound);
    const double bd = b * r.d;
    const double x = r.t - bd;
    const double e =
        (r.et + std::abs(b) * r.ed + u * (std::abs(x) + std::abs(bd))) * (1 + 0x1.0p-48);
    const int sign = certain_sign(x, e);
    return sign == 2 ? 2 : s * sign;
}

/// The nearest float to T / D when the double enclosure of T / D rounds to one float, else NaN.
/// With alpha = et / |T^|, beta = ed / |D^| and one rounding in the division, the exact t lies
/// within |t^| (alpha + beta + u + u beta) / (1 - beta - u) of t^; 4u |t^| more covers the term
/// u beta (< u / 2 here) and the rounding of t^ -+ radius (< 1.5u |t^|), and the (1 + 2^-48)
/// factor the rounding of the radius's own evaluation. Rounding to nearest is monotone, so equal
/// floats at both ends certify the nearest float.
inline float certified_t(const Terms& r) {
    constexpr double u = 0x1.0p-53;
    const double at = std::abs(r.t), ad = std::abs(r.d);
    if (!(at > r.et) || !(ad > r.ed)) {
        return std::numeric_limits<float>::quiet_NaN();  // T near 0 or D uncertain
    }
    const double alpha = r.et / at, beta = r.ed / ad;
    if (alpha + beta > 0.25) {
        return std::numeric_limits<float>::quiet_NaN();
    }
    const double t = r.t / r.d;
    const double rel = (alpha + beta + u) / (1 - beta - u) + 4 * u;
    const double rad = std::abs(t) * rel * (1 + 0x1.0p-48);
    const float lo = static_cast<float>(t - rad), hi = static_cast<float>(t + rad);
    return lo == hi ? lo : std::numeric_limits<float>::quiet_NaN();
}

}  // namespace exact_detail

/// Exact ray/triangle decision in rational arithmetic (never filtered): the reference the filtered
/// path falls back to. Sets fallback = true. Allocates (GMP).
ExactHit exact_intersect_rational(const Rayf& ray,
                                  const Vec3f& p0,
                                  const Vec3f& p1,
                                  const Vec3f& p2);

/// Certified ray/triangle test (see the file comment for the semantics): filtered in double, exact
/// (rational) only when a sign or the rounding of t is within its error bound. The filtered path
/// neither allocates nor calls out of line.
inline ExactHit exact_intersect(const Rayf& ray,
                                const Vec3f& p0,
                                const Vec3f& p1,
                                const Vec3f& p2) {
    using exact_detail::certain_sign;
    const exact_detail::Terms r = exact_detail::evaluate(ray, p0, p1, p2);
    const int su = certain_sign(r.u, r.eu), sv = certain_sign(r.v, r.ev);
    const int sw = certain_sign(r.w, r.ew);
    const bool neg = su == -1 || sv == -1 || sw == -1;
    const bool pos = su == 1 || sv == 1 || sw == 1;
    if (neg && pos) {
        return {};  // certainly outside one edge
    }
    if (su == 2 || sv == 2 || sw == 2) {
        return exact_intersect_rational(ray, p0, p1, p2);
    }
    if (!neg && !pos) {
        return {};  // U = V = W = 0 exactly: D = 0, the ray lies in the plane or area is zero
    }
    // All signs certain and alike, one nonzero: D = U + V + W is nonzero with sign s.
    const int s = pos ? 1 : -1;
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (ray.tmin == inf || ray.tmax == -inf) {
        return {};  // empty window
    }
    const int lo = std::isinf(ray.tmin) ? 1 : exact_detail::window_sign(r, s, ray.tmin);
    const int hi = std::isinf(ray.tmax) ? -1 : exact_detail::window_sign(r, s, ray.tmax);
    if (lo == 2 || hi == 2) {
        return exact_intersect_rational(ray, p0, p1, p2);
    }
    if (lo < 0 || hi > 0) {
        return {};  // t certainly outside [tmin, tmax]
    }
    const float t = exact_detail::certified_t(r);
    if (std::isnan(t)) {
        return exact_intersect_rational(ray, p0, p1, p2);
    }
    return {t, static_cast<float>(r.v / r.d), static_cast<float>(r.w / r.d), true, false};
}

/// Exact comparison of two hit distances along the same ray: sign of tA - tB (-1, 0, +1) for the
/// exact t of ray against triangles A and B. Both must be hits. Rational arithmetic; allocates.
int exact_compare_t(const Rayf& ray, const Trianglef& a, const Trianglef& b);

/// True when hit A (primitive id_a, triangle ta) comes before hit B along ray: smaller exact t, or
/// equal exact t and the lower primitive id. Both must be hits of exact_intersect on this ray.
/// Distinct nearest floats order the exact values (rounding is monotone), so exact arithmetic
/// runs only when both hits round to the same float.
inline bool exact_less(const Rayf& ray,
                       const ExactHit& hit_a,
                       const Trianglef& ta,
                       std::uint32_t id_a,
                       const ExactHit& hit_b,
                       const Trianglef& tb,
                       std::uint32_t id_b) {
    if (hit_a.t != hit_b.t) {
        return hit_a.t < hit_b.t;
    }
    const int c = exact_compare_t(ray, ta, tb);
    return c != 0 ? c < 0 : id_a < id_b;
}

/// The certified test as a float triangle method ("exact"), so the method cross-check measures it
/// beside the float methods; exact mode (trace/exact_query.h) adds the exact closest-hit order.
struct CertifiedTriangle : VertexTriangleMethod<float>, MethodDefaults<CertifiedTriangle> {
    static constexpr std::string_view name = "exact";

    /// The certified hit with t in [ray.tmin, ray.tmax], or nullopt.
    static std::optional<PrimHit<float>> intersect(const Prepared& p, const Rayf& ray) {
        const ExactHit h = exact_intersect(ray, p.p0, p.p1, p.p2);
        return h.hit ? std::optional(PrimHit<float>{h.t, h.u, h.v}) : std::nullopt;
    }
};

static_assert(IntersectionMethod<CertifiedTriangle>);

}  // namespace rtlab
