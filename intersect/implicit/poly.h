#pragma once
// Polynomial: real coefficients c[0] + c[1] t + ... + c[N] t^N of fixed capacity N, evaluated by
// Horner's rule (cost: N multiply-adds), plus the small root list the solvers return.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace rtlab {

/// A polynomial of degree at most N; c[i] is the coefficient of t^i.
template <class T, std::size_t N>
struct Polynomial {
    std::array<T, N + 1> c{};

    /// Value at t (Horner).
    constexpr T operator()(T t) const {
        T v = c[N];
        for (std::size_t i = N; i-- > 0;) {
            v = v * t + c[i];
        }
        return v;
    }

    /// Value and first derivative at t in one Horner pass.
    constexpr void eval(T t, T& value, T& deriv) const {
        value = c[N];
        deriv = T(0);
        for (std::size_t i = N; i-- > 0;) {
            deriv = deriv * t + value;
            value = value * t + c[i];
        }
    }

    /// The derivative, a polynomial of capacity N - 1 (N >= 1).
    constexpr Polynomial<T, (N > 0 ? N - 1 : 0)> derivative() const {
        Polynomial<T, (N > 0 ? N - 1 : 0)> d;
        for (std::size_t i = 1; i <= N; ++i) {
            d.c[i - 1] = static_cast<T>(i) * c[i];
        }
        return d;
    }

    /// Degree after dropping exactly-zero leading coefficients; -1 for the zero polynomial.
    constexpr int degree() const {
        for (std::size_t i = N + 1; i-- > 0;) {
            if (c[i] != T(0)) {
                return static_cast<int>(i);
            }
        }
        return -1;
    }

    /// The polynomial in s = t - t0, i.e. p(t0 + s) (Horner-style Taylor shift, N^2/2 mul-adds).
    constexpr Polynomial shifted(T t0) const {
        Polynomial q = *this;
        constexpr int n = static_cast<int>(N);
        for (int k = 0; k < n; ++k) {
            for (int i = n - 1; i >= k; --i) {
                q.c[static_cast<std::size_t>(i)] += t0 * q.c[static_cast<std::size_t>(i + 1)];
            }
        }
        return q;
    }
};

/// Up to N real roots in ascending order; count says how many entries are valid.
template <class T, std::size_t N>
struct RealRoots {
    std::array<T, N> t{};
    std::size_t count = 0;

    /// Append one root (ignored when full).
    constexpr void push(T r) {
        if (count < N) {
            t[count++] = r;
        }
    }
    /// Sort the valid entries ascending (insertion sort: N <= 4, and GCC 12 -O3 reports a false
    /// -Warray-bounds inside std::sort on a 4-element array).
    constexpr void sort() {
        for (std::size_t i = 1; i < count; ++i) {
            const T v = t[i];
            std::size_t j = i;
            for (; j > 0 && t[j - 1] > v; --j) {
                t[j] = t[j - 1];
            }
            t[j] = v;
        }
    }
    /// Smallest root in [lo, hi], or false.
    constexpr bool first_in(T lo, T hi, T& out) const {
        for (std::size_t i = 0; i < count; ++i) {
            if (t[i] >= lo && t[i] <= hi) {
                out = t[i];
                return true;
            }
        }
        return false;
    }
};

}  // namespace rtlab
