// Exact fallback of the certified ray/triangle test: GMP rationals. Every float is a dyadic
// rational, so the edge functions, D and T are computed without rounding; t is rounded to the
// nearest float through round-to-odd (Boldo & Melquiond 2008).

#include "intersect/triangle/exact_hit.h"

#include <cmath>
#include <gmpxx.h>
#include <limits>

namespace rtlab {

namespace {

struct QVec {
    mpq_class x, y, z;
};

QVec rational(const Vec3f& v) {
    return {mpq_class(static_cast<double>(v.x)), mpq_class(static_cast<double>(v.y)),
            mpq_class(static_cast<double>(v.z))};
}

QVec operator-(const QVec& a, const QVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}

/// d . (b x c), exactly.
mpq_class triple(const QVec& d, const QVec& b, const QVec& c) {
    return mpq_class(d.x * (b.y * c.z - b.z * c.y) + d.y * (b.z * c.x - b.x * c.z) +
                     d.z * (b.x * c.y - b.y * c.x));
}

/// The hit distance as T / D (D = 0: no single hit point), exactly.
struct Distance {
    mpq_class t, d;
};

Distance distance(const Rayf& ray, const Trianglef& tri) {
    const QVec o = rational(ray.org), d = rational(ray.dir);
    const QVec q0 = rational(tri.p0), q1 = rational(tri.p1), q2 = rational(tri.p2);
    return {triple(q0 - o, q1 - o, q2 - o), triple(d, q1 - q0, q2 - q0)};
}

/// The float nearest to x, ties to even. x is first rounded to odd on a grid of at least 52
/// significant bits, exact in double; rounding that double to float then gives the nearest float
/// of x itself, as 52 >= 24 + 2 (Boldo & Melquiond 2008, "Emulation of FMA and correctly rounded
/// sums: proved algorithms using rounding to odd", Theorem 1). Every |x| reached here lies between
/// 2^-840 and 2^840 (ratios of multiples of 2^-447 below 2^390), so the double is normal.
float nearest_float(const mpq_class& x) {
    const int sign = sgn(x);
    if (sign == 0) {
        return 0.0f;
    }
    mpz_class num = abs(x.get_num());
    mpz_class den = x.get_den();
    const long nb = static_cast<long>(mpz_sizeinbase(num.get_mpz_t(), 2));
    const long db = static_cast<long>(mpz_sizeinbase(den.get_mpz_t(), 2));
    // num / den is in [2^(nb-db-1), 2^(nb-db+1)): scaled by 2^s, the quotient is in [2^51, 2^53).
    const long s = 52 - (nb - db);
    if (s >= 0) {
        num <<= static_cast<unsigned long>(s);
    } else {
        den <<= static_cast<unsigned long>(-s);
    }
    mpz_class q, r;
    mpz_tdiv_qr(q.get_mpz_t(), r.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    if (r != 0) {
        q |= 1;  // round to odd: a set last bit records the discarded remainder
    }
    const double scaled = q.get_d();  // exact: q < 2^53
    return static_cast<float>(sign * std::ldexp(scaled, static_cast<int>(-s)));
}

float to_float(const mpq_class& x) {
    return static_cast<float>(x.get_d());
}

}  // namespace

ExactHit exact_intersect_rational(const Rayf& ray,
                                  const Vec3f& p0,
                                  const Vec3f& p1,
                                  const Vec3f& p2) {
    ExactHit h;
    h.fallback = true;
    const QVec o = rational(ray.org), d = rational(ray.dir);
    const QVec q0 = rational(p0), q1 = rational(p1), q2 = rational(p2);
    const QVec a = q0 - o, b = q1 - o, c = q2 - o;
    const mpq_class u = triple(d, b, c), v = triple(d, c, a), w = triple(d, a, b);
    const bool neg = sgn(u) < 0 || sgn(v) < 0 || sgn(w) < 0;
    const bool pos = sgn(u) > 0 || sgn(v) > 0 || sgn(w) > 0;
    const mpq_class det = u + v + w;
    if ((neg && pos) || sgn(det) == 0) {
        return h;  // outside an edge; or parallel, coplanar or degenerate
    }
    const int s = sgn(det);
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (ray.tmin == inf || ray.tmax == -inf) {
        return h;
    }
    const mpq_class t_num = triple(a, b, c);
    const auto beyond = [&](float bound) {
        return s * sgn(t_num - mpq_class(static_cast<double>(bound)) * det);
    };
    if ((!std::isinf(ray.tmin) && beyond(ray.tmin) < 0) ||
        (!std::isinf(ray.tmax) && beyond(ray.tmax) > 0)) {
        return h;  // t outside [tmin, tmax]
    }
    h.hit = true;
    h.t = nearest_float(mpq_class(t_num / det));
    h.u = to_float(mpq_class(v / det));
    h.v = to_float(mpq_class(w / det));
    return h;
}

int exact_compare_t(const Rayf& ray, const Trianglef& a, const Trianglef& b) {
    const Distance da = distance(ray, a);
    const Distance db = distance(ray, b);
    const int c = cmp(mpq_class(da.t / da.d), mpq_class(db.t / db.d));
    return (c > 0) - (c < 0);
}

}  // namespace rtlab
