// Bisection root finder: finds the first simple root in [0, 1] to a few ULPs, and by design misses
// a double (tangent) root, which shows no sign change.
#include "intersect/implicit/bisection.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

using namespace rtlab;

namespace {

/// The monic quartic with roots r[0..3].
Polynomial<double, 4> from_roots(const std::array<double, 4>& r) {
    Polynomial<double, 4> p;
    p.c = {1, 0, 0, 0, 0};
    for (std::size_t k = 0; k < 4; ++k) {  // multiply by (t - r[k])
        for (std::size_t i = k + 1; i > 0; --i) {
            p.c[i] = p.c[i - 1] - r[k] * p.c[i];
        }
        p.c[0] = -r[k] * p.c[0];
    }
    return p;
}

}  // namespace

TEST_CASE("bisection finds the first simple root of a quartic in [0, 1]",
          "[intersect][implicit][roots]") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> in(0.0, 1.0), out(1.5, 4.0);
    for (int i = 0; i < 2000; ++i) {
        // Two roots in [0, 1] at least one marching step (1/16) apart, two outside.
        double a = in(rng), b = in(rng);
        if (std::abs(a - b) < 0.07) {
            continue;
        }
        const auto p = from_roots({a, b, out(rng), -out(rng)});
        const auto root = bisection_first_root(p);
        REQUIRE(root.has_value());
        CHECK(std::abs(*root - std::min(a, b)) <= 1e-12);
    }
}

TEST_CASE("bisection misses a tangent root and reports no root without a sign change",
          "[intersect][implicit][roots]") {
    const auto tangent = from_roots({0.3, 0.3, 2.0, 3.0});  // touches zero at 0.3 only
    CHECK_FALSE(bisection_first_root(tangent).has_value());
    const auto none = from_roots({-1.0, -2.0, 2.0, 3.0});
    CHECK_FALSE(bisection_first_root(none).has_value());
    const auto at_zero = from_roots({0.0, 0.5, 2.0, 3.0});
    REQUIRE(bisection_first_root(at_zero).has_value());
    CHECK(*bisection_first_root(at_zero) == 0.0);
}
