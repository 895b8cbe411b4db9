#pragma once
// Laguerre's method with deflation for all complex roots, then the real ones (Press et al.,
// Numerical Recipes 9.5, "laguer"/"zroots"; fractional steps every 10 iterations break limit
// cycles). Roots are polished on the undeflated polynomial. Cost: ~N * 10 iterations of O(N).

#include "intersect/implicit/poly.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>

namespace rtlab {

namespace detail {

/// One Laguerre root of the complex polynomial a[0..m] from the start x (in place).
template <class T, std::size_t N>
void laguerre_root(const std::array<std::complex<T>, N + 1>& a, std::size_t m, std::complex<T>& x) {
    using C = std::complex<T>;
    constexpr int iters_per_frac = 10;
    constexpr std::array<T, 9> frac{T(0),    T(0.5),  T(0.25), T(0.75), T(0.13),
                                    T(0.38), T(0.62), T(0.88), T(1)};
    const T md = static_cast<T>(m);
    for (int it = 1; it <= iters_per_frac * 8; ++it) {
        C b = a[m], d = C(0), f = C(0);
        T err = std::abs(b);
        const T abx = std::abs(x);
        for (std::size_t j = m; j-- > 0;) {
            f = x * f + d;
            d = x * d + b;
            b = x * b + a[j];
            err = std::abs(b) + abx * err;
        }
        // |b| below the rounding error of its own evaluation: x is a root to working precision.
        if (std::abs(b) <= err * std::numeric_limits<T>::epsilon()) {
            return;
        }
        const C g = d / b;
        const C g2 = g * g;
        const C h = g2 - T(2) * f / b;
        const C sq = std::sqrt((md - T(1)) * (md * h - g2));
        C gp = g + sq;
        const C gm = g - sq;
        const T abp = std::abs(gp), abm = std::abs(gm);
        if (abp < abm) {
            gp = gm;
        }
        const C dx =
            std::max(abp, abm) > T(0) ? md / gp : std::polar(T(1) + abx, static_cast<T>(it));
        const C x1 = x - dx;
        if (x1 == x) {
            return;
        }
        if (it % iters_per_frac != 0) {
            x = x1;
        } else {
            x -= frac[static_cast<std::size_t>(it / iters_per_frac)] * dx;
        }
    }
}

}  // namespace detail

/// All N complex roots of p (degree exactly N, p.c[N] != 0), found one by one from 0 with
/// deflation and polished on p; count is the degree after dropping zero leading coefficients.
template <class T, std::size_t N>
std::array<std::complex<T>, N> laguerre_all_roots(const Polynomial<T, N>& p, std::size_t& count) {
    using C = std::complex<T>;
    std::array<C, N> roots{};
    const int deg = p.degree();
    count = deg > 0 ? static_cast<std::size_t>(deg) : 0;
    std::array<C, N + 1> full{}, work{};
    for (std::size_t i = 0; i <= N; ++i) {
        full[i] = work[i] = C(p.c[i]);
    }
    for (std::size_t m = count; m >= 1; --m) {
        C x(0);
        detail::laguerre_root<T, N>(work, m, x);
        // Snap to the real axis when the imaginary part is rounding noise.
        if (std::abs(x.imag()) <= T(2) * std::numeric_limits<T>::epsilon() * std::abs(x.real())) {
            x = C(x.real());
        }
        roots[m - 1] = x;
        // Deflate by (t - x): synthetic division.
        C b = work[m];
        for (std::size_t j = m; j-- > 0;) {
            const C tmp = work[j];
            work[j] = b;
            b = x * b + tmp;
        }
    }
    for (std::size_t i = 0; i < count; ++i) {
        detail::laguerre_root<T, N>(full, count, roots[i]);
    }
    return roots;
}

/// Real roots of p, ascending: the Laguerre roots x + iy with |y| <= sqrt(eps) (1 + |z|), real
/// parts kept. Why sqrt(eps): close real roots are ill-conditioned and come back with |y| well
/// above rounding (1e-13 in double for roots 1e-3 apart), and a complex pair with |y| below
/// sqrt(eps) has |p| within rounding of 0 between the pair, so it is numerically a double root.
template <class T, std::size_t N>
RealRoots<T, N> laguerre_real_roots(const Polynomial<T, N>& p) {
    std::size_t count = 0;
    const auto roots = laguerre_all_roots(p, count);
    const T rel = std::sqrt(std::numeric_limits<T>::epsilon());
    RealRoots<T, N> r;
    for (std::size_t i = 0; i < count; ++i) {
        if (std::abs(roots[i].imag()) <= rel * (T(1) + std::abs(roots[i]))) {
            r.push(roots[i].real());
        }
    }
    r.sort();
    return r;
}

}  // namespace rtlab
