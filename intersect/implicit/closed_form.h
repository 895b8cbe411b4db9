#pragma once
// Closed-form real roots of polynomials of degree 1-4: stable quadratic (Press et al., Numerical
// Recipes 5.6), cubic by Cardano / the trigonometric form (Viete), quartic by Ferrari's resolvent
// cubic. Each root is polished by up to 2 Newton steps on the input polynomial (kept only when they
// reduce |p|). Cost: one cbrt/acos + a few sqrt; no iteration beyond polishing.

#include "intersect/implicit/poly.h"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace rtlab {

namespace detail {

/// Up to two Newton steps on p from t, each kept only when it lowers |p| (documented polish).
template <class T, std::size_t N>
T polish_root(const Polynomial<T, N>& p, T t) {
    T v, d;
    p.eval(t, v, d);
    for (int i = 0; i < 2 && v != T(0) && d != T(0); ++i) {
        const T tn = t - v / d;
        T vn, dn;
        p.eval(tn, vn, dn);
        if (!(std::abs(vn) < std::abs(v))) {
            break;
        }
        t = tn;
        v = vn;
        d = dn;
    }
    return t;
}

/// Relative tolerance under which a negative discriminant is taken as a double root: a few ulps
/// of the terms it is computed from, so exact double roots (tangency) survive rounding.
template <class T>
constexpr T disc_slack() {
    return T(8) * std::numeric_limits<T>::epsilon();
}

}  // namespace detail

/// Real roots of c0 + c1 t = 0 (none when c1 == 0).
template <class T>
RealRoots<T, 4> solve_linear(T c0, T c1) {
    RealRoots<T, 4> r;
    if (c1 != T(0)) {
        r.push(-c0 / c1);
    }
    return r;
}

/// Real roots of c0 + c1 t + c2 t^2, ascending; a double root is reported twice. Stable form
/// q = -(c1 + sign(c1) sqrt(disc)) / 2, roots q/c2 and c0/q (Numerical Recipes 5.6).
template <class T>
RealRoots<T, 4> solve_quadratic(T c0, T c1, T c2) {
    if (c2 == T(0)) {
        return solve_linear(c0, c1);
    }
    RealRoots<T, 4> r;
    T disc = c1 * c1 - T(4) * c2 * c0;
    if (disc < T(0)) {
        if (-disc > detail::disc_slack<T>() * (c1 * c1 + std::abs(T(4) * c2 * c0))) {
            return r;
        }
        disc = T(0);
    }
    const T q = T(-0.5) * (c1 + std::copysign(std::sqrt(disc), c1));
    const T t0 = q / c2;
    const T t1 = q != T(0) ? c0 / q : t0;
    r.push(std::min(t0, t1));
    r.push(std::max(t0, t1));
    return r;
}

/// Real roots of c0 + c1 t + c2 t^2 + c3 t^3, ascending (Cardano for one real root, Viete's
/// trigonometric form for three); multiple roots are reported with multiplicity when detected.
template <class T>
RealRoots<T, 4> solve_cubic(T c0, T c1, T c2, T c3) {
    if (c3 == T(0)) {
        return solve_quadratic(c0, c1, c2);
    }
    // Monic t^3 + a t^2 + b t + c, depressed by t = x - a/3 to x^3 + p x + q.
    const T a = c2 / c3, b = c1 / c3, c = c0 / c3;
    const T shift = a / T(3);
    const T p = b - a * shift;
    const T q = T(2) * a * a * a / T(27) - a * b / T(3) + c;
    const T half_q = q / T(2), third_p = p / T(3);
    const T disc = half_q * half_q + third_p * third_p * third_p;
    const T slack =
        detail::disc_slack<T>() * (half_q * half_q + std::abs(third_p * third_p * third_p));
    RealRoots<T, 4> r;
    if (disc > slack) {
        // One real root (Cardano); A and B chosen so A + B does not cancel.
        const T big = std::cbrt(std::abs(half_q) + std::sqrt(disc));
        const T A = half_q > T(0) ? -big : big;
        const T B = A != T(0) ? -third_p / A : T(0);
        r.push(A + B - shift);
    } else if (p == T(0)) {
        r.push(-shift);  // triple root (q == 0 as well, up to rounding)
        r.push(-shift);
        r.push(-shift);
    } else if (disc >= -slack) {
        // Double root: x = -3q / (2p) (twice) and 3q / p.
        const T xd = T(-1.5) * q / p;
        r.push(xd - shift);
        r.push(xd - shift);
        r.push(T(3) * q / p - shift);
    } else {
        // Three distinct real roots (Viete): x_k = 2 sqrt(-p/3) cos(phi/3 - 2 pi k / 3).
        const T m = T(2) * std::sqrt(-third_p);
        const T arg = std::clamp(T(3) * q / (p * m), T(-1), T(1));
        const T phi = std::acos(arg) / T(3);
        const T two_thirds_pi = T(2) * std::numbers::pi_v<T> / T(3);
        for (int k = 0; k < 3; ++k) {
            r.push(m * std::cos(phi - two_thirds_pi * static_cast<T>(k)) - shift);
        }
    }
    const Polynomial<T, 3> poly{{c0, c1, c2, c3}};
    for (std::size_t i = 0; i < r.count; ++i) {
        r.t[i] = detail::polish_root(poly, r.t[i]);
    }
    r.sort();
    return r;
}

/// Real roots of c0 + c1 t + ... + c4 t^4, ascending (Ferrari: depressed quartic split into two
/// quadratics by the largest root of the resolvent cubic); then polished on the input.
template <class T>
RealRoots<T, 4> solve_quartic(T c0, T c1, T c2, T c3, T c4) {
    if (c4 == T(0)) {
        return solve_cubic(c0, c1, c2, c3);
    }
    // Monic t^4 + a t^3 + b t^2 + c t + d, depressed by t = x - a/4 to x^4 + p x^2 + q x + r.
    const T a = c3 / c4, b = c2 / c4, c = c1 / c4, d = c0 / c4;
    const T shift = a / T(4);
    const T a2 = a * a;
    const T p = b - T(3) * a2 / T(8);
    const T q = c - a * b / T(2) + a2 * a / T(8);
    const T r = d - a * c / T(4) + a2 * b / T(16) - T(3) * a2 * a2 / T(256);
    RealRoots<T, 4> out;
    const T scale = std::abs(c) + std::abs(a * b / T(2)) + std::abs(a2 * a / T(8));
    // Resolvent cubic 8 m^3 + 8 p m^2 + (2 p^2 - 8 r) m - q^2 = 0 has a root m > 0 when q != 0;
    // then x^4 + p x^2 + q x + r = (x^2 + p/2 + m)^2 - 2m (x - q/(4m))^2. When q is rounding noise
    // (or m underflows to <= 0) the quartic is treated as biquadratic.
    T m = T(0);
    if (std::abs(q) > detail::disc_slack<T>() * scale) {
        const RealRoots<T, 4> ms = solve_cubic(-q * q, T(2) * p * p - T(8) * r, T(8) * p, T(8));
        m = ms.count > 0 ? ms.t[ms.count - 1] : T(0);
    }
    if (m > T(0)) {
        const T s = std::sqrt(T(2) * m);
        const T k = q / (T(2) * s);
        const RealRoots<T, 4> r1 = solve_quadratic(p / T(2) + m + k, -s, T(1));
        const RealRoots<T, 4> r2 = solve_quadratic(p / T(2) + m - k, s, T(1));
        for (std::size_t i = 0; i < r1.count; ++i) {
            out.push(r1.t[i] - shift);
        }
        for (std::size_t i = 0; i < r2.count; ++i) {
            out.push(r2.t[i] - shift);
        }
    } else {
        // Biquadratic: y = x^2 solves y^2 + p y + r = 0.
        const RealRoots<T, 4> ys = solve_quadratic(r, p, T(1));
        for (std::size_t i = 0; i < ys.count; ++i) {
            if (ys.t[i] > T(0)) {
                const T x = std::sqrt(ys.t[i]);
                out.push(-x - shift);
                out.push(x - shift);
            } else if (ys.t[i] >=
                       -detail::disc_slack<T>() * (std::abs(p) + std::sqrt(std::abs(r)))) {
                out.push(-shift);
            }
        }
    }
    const Polynomial<T, 4> poly{{c0, c1, c2, c3, c4}};
    for (std::size_t i = 0; i < out.count; ++i) {
        out.t[i] = detail::polish_root(poly, out.t[i]);
    }
    out.sort();
    return out;
}

/// Real roots of p (degree <= 4 after dropping exactly-zero leading coefficients), ascending.
template <class T, std::size_t N>
RealRoots<T, 4> solve_closed_form(const Polynomial<T, N>& p) {
    static_assert(N <= 4, "closed forms exist up to degree 4");
    std::array<T, 5> c{};
    for (std::size_t i = 0; i <= N; ++i) {
        c[i] = p.c[i];
    }
    return solve_quartic(c[0], c[1], c[2], c[3], c[4]);
}

/// Real roots of p on the window u in [0, 1] (ascending; roots outside [0, 1] may be reported as
/// well): leading coefficients too small to change any value of p on [0, 1] are dropped first. A
/// term c_k u^k is at most |c_k| there, so when |c_k| <= N eps (|c_0| + ... + |c_{k-1}|), below
/// the rounding error of evaluating p (Higham, Accuracy and Stability, 5.1: Horner's bound), the
/// computed polynomial cannot tell it from 0. Keeping it instead divides every other coefficient
/// by it (Ferrari, Cardano), and the noise of that division gives roots p does not have: a
/// shadow ray leaving a torus crest has a quartic like 1.2e-5 + 2.4e-4 u + 1.4e-7 u^2 + 3.9e-11 u^3
/// + 5.1e-15 u^4 (no root in [0, 1]) for which Ferrari in float reports u = 0.10.
template <class T, std::size_t N>
RealRoots<T, 4> solve_closed_form_unit(const Polynomial<T, N>& p) {
    static_assert(N <= 4, "closed forms exist up to degree 4");
    std::array<T, 5> c{};
    for (std::size_t i = 0; i <= N; ++i) {
        c[i] = p.c[i];
    }
    const T bound = T(N) * std::numeric_limits<T>::epsilon();
    for (std::size_t k = N; k > 0; --k) {
        T lower = T(0);
        for (std::size_t i = 0; i < k; ++i) {
            lower += std::abs(c[i]);
        }
        if (!(std::abs(c[k]) <= bound * lower)) {
            break;
        }
        c[k] = T(0);
    }
    return solve_quartic(c[0], c[1], c[2], c[3], c[4]);
}

}  // namespace rtlab
