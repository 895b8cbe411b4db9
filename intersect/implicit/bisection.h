#pragma once
// Plain bisection on a sign change (Bolzano; Press et al., Numerical Recipes 9.1): the window
// [0, 1] is marched in `steps` equal intervals and the first with a sign change of p is halved
// until it is a few ulps wide. Cost: steps + ~log2(1 / (steps eps)) evaluations of p (about
// 16 + 20 in float, 16 + 49 in double). By design it misses a root pair inside one step and a
// tangent (double) root, which show no sign change: the baseline the other finders improve on.

#include "intersect/implicit/poly.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

namespace rtlab {

/// Smallest u in [0, 1] at which poly changes sign (or is exactly 0) found by marching `steps`
/// intervals and bisecting the first bracket for at most max_iter halvings; nullopt when no
/// sampled interval changes sign.
template <class T, std::size_t N>
std::optional<T> bisection_first_root(const Polynomial<T, N>& poly,
                                      int steps = 16,
                                      int max_iter = 200) {
    T ua = T(0);
    T va = poly(ua);
    if (va == T(0)) {
        return ua;
    }
    for (int i = 1; i <= steps; ++i) {
        const T ub = static_cast<T>(i) / static_cast<T>(steps);
        const T vb = poly(ub);
        if (vb == T(0)) {
            return ub;
        }
        if ((va < T(0)) != (vb < T(0))) {
            // Halve [lo, hi], keeping the sign change; stop a few ulps from the midpoint (the
            // bracket cannot shrink further in T).
            T lo = ua, hi = ub;
            const bool lo_negative = va < T(0);
            for (int k = 0; k < max_iter; ++k) {
                const T mid = (lo + hi) / T(2);
                if (mid <= lo || mid >= hi ||
                    hi - lo <= T(4) * std::numeric_limits<T>::epsilon() * std::abs(mid)) {
                    break;
                }
                const T vm = poly(mid);
                if (vm == T(0)) {
                    return mid;
                }
                ((vm < T(0)) == lo_negative ? lo : hi) = mid;
            }
            return (lo + hi) / T(2);
        }
        ua = ub;
        va = vb;
    }
    return std::nullopt;
}

}  // namespace rtlab
