#pragma once
// Newton's method safeguarded by bisection on a sign-change bracket (the "rtsafe" scheme of Press
// et al., Numerical Recipes 9.4), with an analytic derivative or a central-difference one (as the
// seed 001 tracer does). Cost: <= max_iter evaluations; stops when the bracket is a few ulps wide.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace rtlab {

/// Root of f in [lo, hi] given f(lo) and f(hi) of opposite signs (or one of them zero).
/// fdf(t) returns {f(t), f'(t)}. A Newton step is taken when it stays inside the bracket and
/// halves |f| at least as well as bisection would shrink the bracket; otherwise the bracket is
/// bisected. Returns nullopt when the bracket has no sign change.
template <class T, class Fdf>
std::optional<T> newton_bisect(Fdf&& fdf, T lo, T hi, int max_iter = 100) {
    const T flo = fdf(lo).first;
    const T fhi = fdf(hi).first;
    if (flo == T(0)) {
        return lo;
    }
    if (fhi == T(0)) {
        return hi;
    }
    if ((flo < T(0)) == (fhi < T(0))) {
        return std::nullopt;
    }
    // Orient so that f(neg) < 0 < f(pos).
    T neg = flo < T(0) ? lo : hi;
    T pos = flo < T(0) ? hi : lo;
    T t = (lo + hi) / T(2);
    T dx_old = std::abs(hi - lo);
    T dx = dx_old;
    std::pair<T, T> fd = fdf(t);
    T f = fd.first, df = fd.second;
    for (int i = 0; i < max_iter; ++i) {
        const T newton = t - f / df;
        const bool outside = !(newton > std::min(neg, pos) && newton < std::max(neg, pos));
        const bool slow = std::abs(T(2) * f) > std::abs(dx_old * df);
        dx_old = dx;
        if (df == T(0) || outside || slow) {
            dx = (pos - neg) / T(2);
            t = neg + dx;
        } else {
            dx = f / df;
            t = newton;
        }
        // Converged when the step is below a few ulps of t (or the bracket collapsed).
        const T tol = T(4) * std::numeric_limits<T>::epsilon() * std::abs(t);
        if (std::abs(dx) <= tol || std::abs(pos - neg) <= tol) {
            return t;
        }
        fd = fdf(t);
        f = fd.first;
        df = fd.second;
        if (f == T(0)) {
            return t;
        }
        (f < T(0) ? neg : pos) = t;
    }
    return t;
}

/// Wraps f into the {f, f'} form of newton_bisect with a central difference of step
/// h = cbrt(eps) max(1, |t|) (error O(h^2), the optimum for a central difference).
template <class T, class F>
auto numeric_derivative(F&& f) {
    return [f = std::forward<F>(f)](T t) {
        const T h = std::cbrt(std::numeric_limits<T>::epsilon()) * std::max(T(1), std::abs(t));
        return std::pair<T, T>{f(t), (f(t + h) - f(t - h)) / (T(2) * h)};
    };
}

}  // namespace rtlab
