// Exact references (see exact.h): sphere roots from the rational quadratic with an MPFR square
// root, triangles by Cramer's rule over Q, polynomial roots by Sturm sequences over Q refined in
// MPFR (moved here from implicit_check.cpp so the stability suite shares them).
#include "crosscheck/exact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mpfr.h>
#include <stdexcept>
#include <utility>

namespace rtlab::xcheck {

double mpfr_root(const mpq_class& a, const mpq_class& b, const mpq_class& disc, int sign) {
    mpfr_t x, y;
    mpfr_inits2(256, x, y, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_q(x, disc.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(x, x, MPFR_RNDN);
    if (sign < 0) {
        mpfr_neg(x, x, MPFR_RNDN);
    }
    mpfr_set_q(y, b.get_mpq_t(), MPFR_RNDN);
    mpfr_sub(x, x, y, MPFR_RNDN);
    mpfr_set_q(y, a.get_mpq_t(), MPFR_RNDN);
    mpfr_div(x, x, y, MPFR_RNDN);
    const double t = mpfr_get_d(x, MPFR_RNDN);
    mpfr_clears(x, y, static_cast<mpfr_ptr>(nullptr));
    return t;
}

namespace {

using Q = mpq_class;

/// A polynomial over Q, ascending coefficients, no zero leading coefficient (empty = 0).
using QPoly = std::vector<Q>;

void trim(QPoly& p) {
    while (!p.empty() && p.back() == 0) {
        p.pop_back();
    }
}

Q eval(const QPoly& p, const Q& x) {
    Q v = 0;
    for (std::size_t i = p.size(); i-- > 0;) {
        v = v * x + p[i];
    }
    return v;
}

int sign(const Q& x) {
    return sgn(x);
}

/// Remainder of a divided by b (b non-zero).
QPoly remainder(QPoly a, const QPoly& b) {
    while (a.size() >= b.size() && !a.empty()) {
        const Q f = a.back() / b.back();
        const std::size_t shift = a.size() - b.size();
        for (std::size_t i = 0; i < b.size(); ++i) {
            a[i + shift] -= f * b[i];
        }
        a.pop_back();  // the leading term cancels exactly
        trim(a);
    }
    return a;
}

/// The Sturm sequence p, p', -rem(p, p'), ... down to the last non-zero remainder.
std::vector<QPoly> sturm(const QPoly& p) {
    std::vector<QPoly> seq{p};
    QPoly d;
    for (std::size_t i = 1; i < p.size(); ++i) {
        d.push_back(p[i] * static_cast<long>(i));
    }
    trim(d);
    if (d.empty()) {
        return seq;
    }
    seq.push_back(d);
    for (;;) {
        QPoly r = remainder(seq[seq.size() - 2], seq.back());
        if (r.empty()) {
            break;
        }
        for (Q& c : r) {
            c = -c;
        }
        seq.push_back(std::move(r));
    }
    return seq;
}

/// Sign variations of the sequence at x (zeros skipped).
int variations(const std::vector<QPoly>& seq, const Q& x) {
    int count = 0, last = 0;
    for (const QPoly& p : seq) {
        const int s = sign(eval(p, x));
        if (s != 0) {
            count += (last != 0 && s != last) ? 1 : 0;
            last = s;
        }
    }
    return count;
}

/// p(x) in MPFR for the n coefficients c (ascending), at the precision of out.
void eval_mpfr(const mpfr_t* c, std::size_t n, const mpfr_t x, mpfr_t out) {
    mpfr_set(out, c[n - 1], MPFR_RNDN);
    for (std::size_t i = n - 1; i-- > 0;) {
        mpfr_mul(out, out, x, MPFR_RNDN);
        mpfr_add(out, out, c[i], MPFR_RNDN);
    }
}

Q exact(double x) {
    return Q(x);
}

/// The sphere's ray quadratic a t^2 + 2 b t + c over Q.
void sphere_quadratic(const Vec3d& center, double radius, const Rayd& ray, Q& a, Q& b, Q& c) {
    a = 0;
    b = 0;
    c = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const Q f = exact(ray.org[k]) - exact(center[k]);
        const Q d = exact(ray.dir[k]);
        a += d * d;
        b += f * d;
        c += f * f;
    }
    c -= exact(radius) * exact(radius);
}

/// Sign of root(s) - x for the root (-b + s sqrt(disc)) / a (a > 0, disc >= 0), exactly:
/// s sqrt(disc) against y = a x + b.
int root_minus(const Q& a, const Q& b, const Q& disc, int s, const Q& x) {
    const Q y = a * x + b;
    if (s > 0) {
        // sqrt(disc) - y
        if (y < 0) {
            return 1;
        }
        const Q diff = disc - y * y;
        return sgn(diff);
    }
    // -sqrt(disc) - y
    if (y > 0) {
        return -1;
    }
    const Q diff = y * y - disc;
    return sgn(diff);
}

/// An exact candidate t: a rational, or the quadric root (-b + s sqrt(disc)) / a (a > 0).
struct Candidate {
    bool valid = false;
    bool is_root = false;
    Q value;  ///< the rational (when !is_root)
    int s = 0;
};

/// Sign of candidate - x.
int minus(const Candidate& c, const Q& a, const Q& b, const Q& disc, const Q& x) {
    return c.is_root ? root_minus(a, b, disc, c.s, x) : sgn(c.value - x);
}

std::array<Q, 3> q3(const Vec3d& v) {
    return {Q(v.x), Q(v.y), Q(v.z)};
}

Q dot3(const std::array<Q, 3>& x, const std::array<Q, 3>& y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

/// A cone (or cylinder) and a ray in rationals: the side is g(t) = a t^2 + 2 b t + c = 0 with
/// 0 <= s0 + t sd <= E (w.e along the axis e = apex - base, E = e.e), a >= 0.
struct ConeQuadric {
    std::array<Q, 3> d, w0, wa;  ///< direction; origin - base; origin - apex
    Q r0, r1, big_e, s0, sd;
    Q a, b, c;

    ConeQuadric(const Cone<double>& cone, const Rayd& ray)
        : d(q3(ray.dir)), r0(cone.base_radius), r1(cone.apex_radius) {
        const std::array<Q, 3> base = q3(cone.base), apex = q3(cone.apex), o = q3(ray.org);
        std::array<Q, 3> e;
        for (std::size_t k = 0; k < 3; ++k) {
            e[k] = apex[k] - base[k];
            w0[k] = o[k] - base[k];
            wa[k] = o[k] - apex[k];
        }
        big_e = dot3(e, e);
        s0 = dot3(w0, e);
        sd = dot3(d, e);  // w.e = s0 + t sd
        const Q l0 = r0 * big_e + (r1 - r0) * s0, ld = (r1 - r0) * sd;
        const Q dd = dot3(d, d);
        a = big_e * big_e * dd - big_e * sd * sd - ld * ld;
        b = big_e * big_e * dot3(w0, d) - big_e * s0 * sd - l0 * ld;
        c = big_e * big_e * dot3(w0, w0) - big_e * s0 * s0 - l0 * l0;
        if (a < 0) {
            a = -a;
            b = -b;
            c = -c;
        }
    }
};

/// The first side point in the ray's window and the slab 0 <= w.e <= E (invalid when none);
/// disc is b^2 - a c when the side is a quadric (a != 0), else 0.
Candidate cone_side(const ConeQuadric& q, const Rayd& ray, Q& disc) {
    // The t interval [lo, hi] of the window and the slab (hi absent when +inf).
    Q lo(ray.tmin);
    bool has_hi = std::isfinite(ray.tmax);
    Q hi(has_hi ? ray.tmax : 0.0);
    bool slab_empty = false;
    if (q.sd == 0) {
        slab_empty = q.s0 < 0 || q.s0 > q.big_e;
    } else {
        Q ta = -q.s0 / q.sd, tb = (q.big_e - q.s0) / q.sd;
        if (ta > tb) {
            std::swap(ta, tb);
        }
        lo = std::max(lo, ta);
        hi = has_hi ? std::min(hi, tb) : tb;
        has_hi = true;
    }
    const auto in_window = [&](const Candidate& cand) {
        return minus(cand, q.a, q.b, disc, lo) >= 0 &&
               (!has_hi || minus(cand, q.a, q.b, disc, hi) <= 0);
    };
    Candidate side;
    disc = 0;
    if (slab_empty || (has_hi && lo > hi)) {
        return side;
    }
    if (q.a == 0) {
        if (q.b != 0) {
            side = {true, false, -q.c / (2 * q.b), 0};
            side.valid = in_window(side);
        } else if (q.c == 0) {
            side = {true, false, lo, 0};  // the line lies in the surface: first point on it
        }
        return side;
    }
    disc = q.b * q.b - q.a * q.c;
    if (disc >= 0) {
        for (int sgn_root : {-1, +1}) {
            const Candidate cand{true, true, Q(0), sgn_root};
            if (in_window(cand)) {
                return cand;
            }
        }
    }
    return side;
}

/// The nearest cap point: rational t on the planes w.e = 0 and w.e = E, inside the disk, inside
/// the ray's window (invalid when none).
Candidate cone_cap(const ConeQuadric& q, const Cone<double>& cone, const Rayd& ray) {
    Candidate cap;
    const Q tmin(ray.tmin);
    const bool finite_max = std::isfinite(ray.tmax);
    const Q tmax(finite_max ? ray.tmax : 0.0);
    const auto try_cap = [&](const Q& t, const std::array<Q, 3>& from, const Q& radius) {
        if (t < tmin || (finite_max && t > tmax)) {
            return;
        }
        std::array<Q, 3> p;
        for (std::size_t k = 0; k < 3; ++k) {
            p[k] = from[k] + t * q.d[k];
        }
        if (dot3(p, p) <= radius * radius && (!cap.valid || t < cap.value)) {
            cap = {true, false, t, 0};
        }
    };
    if (q.sd != 0) {
        if (has_cap(cone.caps, ConeCaps::base)) {
            try_cap(-q.s0 / q.sd, q.w0, q.r0);
        }
        if (has_cap(cone.caps, ConeCaps::apex)) {
            try_cap((q.big_e - q.s0) / q.sd, q.wa, q.r1);
        }
    }
    return cap;
}

}  // namespace

ExactRoot exact_cone_root(const Cone<double>& cone, const Rayd& ray) {
    const ConeQuadric q(cone, ray);
    Q disc;
    const Candidate side = cone_side(q, ray, disc);
    const Candidate cap = cone_cap(q, cone, ray);
    const auto value = [&](const Candidate& cand) {
        return cand.is_root ? mpfr_root(q.a, q.b, disc, cand.s) : cand.value.get_d();
    };
    if (side.valid && (!cap.valid || minus(side, q.a, q.b, disc, cap.value) <= 0)) {
        return {true, value(side)};
    }
    if (cap.valid) {
        return {true, value(cap)};
    }
    return {};
}

bool exact_sphere_roots(
    const Vec3d& center, double radius, const Rayd& ray, double& t0, double& t1) {
    Q a, b, c;
    sphere_quadratic(center, radius, ray, a, b, c);
    const Q disc = b * b - a * c;
    if (disc < 0) {
        return false;
    }
    t0 = mpfr_root(a, b, disc, -1);
    t1 = mpfr_root(a, b, disc, +1);
    return true;
}

ExactRoot exact_sphere_root(const Vec3d& center, double radius, const Rayd& ray) {
    Q a, b, c;
    sphere_quadratic(center, radius, ray, a, b, c);
    const Q disc = b * b - a * c;
    if (disc < 0) {
        return {};
    }
    const Q tmin(ray.tmin);
    const bool finite_max = std::isfinite(ray.tmax);
    const Q tmax(finite_max ? ray.tmax : 0.0);
    for (int s : {-1, +1}) {
        if (root_minus(a, b, disc, s, tmin) >= 0 &&
            (!finite_max || root_minus(a, b, disc, s, tmax) <= 0)) {
            return {true, mpfr_root(a, b, disc, s)};
        }
    }
    return {};
}

ExactTriangleHit exact_triangle_hit(const Triangled& tri, const Rayd& ray) {
    const auto q = [](const Vec3d& v) { return std::array<Q, 3>{Q(v.x), Q(v.y), Q(v.z)}; };
    const auto sub = [](const std::array<Q, 3>& x, const std::array<Q, 3>& y) {
        return std::array<Q, 3>{x[0] - y[0], x[1] - y[1], x[2] - y[2]};
    };
    const auto crs = [](const std::array<Q, 3>& x, const std::array<Q, 3>& y) {
        return std::array<Q, 3>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                                x[0] * y[1] - x[1] * y[0]};
    };
    const auto dt = [](const std::array<Q, 3>& x, const std::array<Q, 3>& y) {
        return Q(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]);
    };
    const std::array<Q, 3> p0 = q(tri.p0), e1 = sub(q(tri.p1), p0), e2 = sub(q(tri.p2), p0);
    const std::array<Q, 3> d = q(ray.dir), s = sub(q(ray.org), p0);
    const std::array<Q, 3> pv = crs(d, e2);
    const Q det = dt(e1, pv);
    ExactTriangleHit out;
    if (det == 0) {
        out.boundary = true;
        return out;
    }
    const Q u = dt(s, pv) / det;
    const std::array<Q, 3> qv = crs(s, e1);
    const Q v = dt(d, qv) / det;
    const Q w = 1 - u - v;
    const Q t = dt(e2, qv) / det;
    if (u < 0 || v < 0 || w < 0) {
        return out;
    }
    if (t < Q(ray.tmin) || (std::isfinite(ray.tmax) && t > Q(ray.tmax))) {
        return out;
    }
    out.boundary = u == 0 || v == 0 || w == 0;
    out.hit = true;
    out.t = t.get_d();
    return out;
}

namespace {

/// The end of the search interval from lo: tmax, or for an unbounded window the Cauchy bound
/// (every root is below 1 + max |c_i / c_n|).
Q search_end(const QPoly& p, const Q& lo, double tmax) {
    if (!std::isinf(tmax)) {
        return Q(tmax);
    }
    Q bound = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        bound = std::max<Q>(bound, abs(p[i] / p.back()));
    }
    return std::max<Q>(bound + 1, lo + 1);
}

/// One bisection of (lo, hi] (v_lo: Sturm variations at lo) by Sturm counts: the lower half when
/// it holds a root, else the upper. Returns the distinct roots in the lower half (0: upper kept).
int sturm_halve(const std::vector<QPoly>& seq, Q& lo, Q& hi, int& v_lo) {
    const Q mid = (lo + hi) / 2;
    const int v_mid = variations(seq, mid);
    const int below = v_lo - v_mid;
    if (below >= 1) {
        hi = mid;
    } else {
        lo = mid;
        v_lo = v_mid;
    }
    return below;
}

/// A root of even multiplicity (exact tangency, no sign change) isolated in (lo, hi]: bisected by
/// Sturm counts to the double nearest the interval's middle.
double sturm_bisect(const std::vector<QPoly>& seq, Q lo, Q hi, int v_lo) {
    for (int step = 0; step < 130; ++step) {
        sturm_halve(seq, lo, hi, v_lo);
    }
    return Q((lo + hi) / 2).get_d();
}

/// A simple (odd-multiplicity) root with a sign change in (lo, hi): 256-bit MPFR bisection to
/// 2^-110 relative; coefficients rounded to 256 bits, far below the 110 bits the refinement
/// needs. Degree at most 4.
double mpfr_bisect(const QPoly& p, const Q& lo, const Q& hi) {
    const int s_lo = sign(eval(p, lo));
    if (p.size() > 5) {
        throw std::logic_error("implicit oracle: degree above 4");
    }
    mpfr_t c[5];
    for (std::size_t i = 0; i < p.size(); ++i) {
        mpfr_init2(c[i], 256);
        mpfr_set_q(c[i], p[i].get_mpq_t(), MPFR_RNDN);
    }
    mpfr_t a, b, m, v, w;
    mpfr_inits2(256, a, b, m, v, w, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_q(a, lo.get_mpq_t(), MPFR_RNDN);
    mpfr_set_q(b, hi.get_mpq_t(), MPFR_RNDN);
    for (int step = 0; step < 600; ++step) {
        mpfr_add(m, a, b, MPFR_RNDN);
        mpfr_div_2ui(m, m, 1, MPFR_RNDN);
        mpfr_sub(w, b, a, MPFR_RNDN);
        mpfr_abs(v, m, MPFR_RNDN);
        mpfr_mul_2si(v, v, -110, MPFR_RNDN);
        if (mpfr_cmp(w, v) <= 0) {
            break;
        }
        eval_mpfr(c, p.size(), m, v);
        if (mpfr_sgn(v) == 0) {
            break;
        }
        if (mpfr_sgn(v) == s_lo) {
            mpfr_set(a, m, MPFR_RNDN);
        } else {
            mpfr_set(b, m, MPFR_RNDN);
        }
    }
    const double t = mpfr_get_d(m, MPFR_RNDN);
    mpfr_clears(a, b, m, v, w, static_cast<mpfr_ptr>(nullptr));
    for (std::size_t i = 0; i < p.size(); ++i) {
        mpfr_clear(c[i]);
    }
    return t;
}

}  // namespace

ExactRoot exact_first_root(std::vector<mpq_class> p, double tmin, double tmax) {
    trim(p);
    ExactRoot out;
    if (p.size() < 2) {
        return out;  // constant along the ray (a zero polynomial cannot occur for d != 0)
    }
    Q lo(tmin);
    if (eval(p, lo) == 0) {
        return {true, tmin};
    }
    Q hi = search_end(p, lo, tmax);
    const std::vector<QPoly> seq = sturm(p);
    int v_lo = variations(seq, lo);
    int n = v_lo - variations(seq, hi);  // distinct roots in (lo, hi]
    if (n <= 0) {
        return out;
    }
    out.hit = true;
    // Isolate the smallest root: keep the lower half whenever it holds a root.
    for (int step = 0; step < 400 && n > 1; ++step) {
        const int below = sturm_halve(seq, lo, hi, v_lo);
        if (below >= 1) {
            n = below;
        }
    }
    if (eval(p, hi) == 0) {
        out.t = hi.get_d();
    } else if (sign(eval(p, lo)) == sign(eval(p, hi))) {
        out.t = sturm_bisect(seq, lo, hi, v_lo);
    } else {
        out.t = mpfr_bisect(p, lo, hi);
    }
    return out;
}

std::vector<mpq_class> exact_torus_along(const Torus<double>& s, const Vec3d& o, const Vec3d& d) {
    Q a = 0, b = 0, c = 0, ea = 0, eb = 0, ec = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const Q qk = exact(o[k]) - exact(s.center[k]);
        const Q dk = exact(d[k]);
        a += dk * dk;
        b += 2 * qk * dk;
        c += qk * qk;
        if (k < 2) {
            ea += dk * dk;
            eb += 2 * qk * dk;
            ec += qk * qk;
        }
    }
    const Q big = exact(s.major), small = exact(s.minor);
    c += big * big - small * small;
    const Q r4 = 4 * big * big;
    return {c * c - r4 * ec, 2 * b * c - r4 * eb, b * b + 2 * a * c - r4 * ea, 2 * a * b, a * a};
}

}  // namespace rtlab::xcheck
