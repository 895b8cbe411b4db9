// Root finders: closed forms against known roots (including multiple roots), Newton with analytic
// and numerical derivatives, Laguerre's method with deflation.
#include "intersect/implicit/closed_form.h"
#include "intersect/implicit/laguerre.h"
#include "intersect/implicit/newton.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtlab;

namespace {

/// Coefficients (ascending) of prod (t - r_i) for four roots.
Polynomial<double, 4> from_roots(double a, double b, double c, double d) {
    Polynomial<double, 4> p{{1, 0, 0, 0, 0}};
    for (const double r : {a, b, c, d}) {
        for (std::size_t i = 4; i > 0; --i) {
            p.c[i] = p.c[i - 1] - r * p.c[i];
        }
        p.c[0] = -r * p.c[0];
    }
    return p;
}

}  // namespace

TEST_CASE("closed forms: linear, quadratic, cubic", "[intersect][roots]") {
    const auto lin = solve_linear(6.0, -2.0);
    REQUIRE(lin.count == 1);
    CHECK(lin.t[0] == Approx(3));
    CHECK(solve_linear(1.0, 0.0).count == 0);

    const auto q = solve_quadratic(-6.0, 1.0, 1.0);  // (t - 2)(t + 3)
    REQUIRE(q.count == 2);
    CHECK(q.t[0] == Approx(-3));
    CHECK(q.t[1] == Approx(2));
    CHECK(solve_quadratic(1.0, 0.0, 1.0).count == 0);
    const auto dq = solve_quadratic(1.0, -2.0, 1.0);  // (t - 1)^2
    REQUIRE(dq.count == 2);
    CHECK(dq.t[0] == Approx(1));
    // Cancellation-prone: roots 1e-8 and 1e8; the stable form gets both to full precision.
    const auto far = solve_quadratic(1.0, -(1e8 + 1e-8), 1.0);
    REQUIRE(far.count == 2);
    CHECK(far.t[0] == Approx(1e-8).epsilon(1e-14));
    CHECK(far.t[1] == Approx(1e8).epsilon(1e-14));

    const auto c3 = solve_cubic(6.0, -5.0, -2.0, 1.0);  // (t - 1)(t + 2)(t - 3)
    REQUIRE(c3.count == 3);
    CHECK(c3.t[0] == Approx(-2));
    CHECK(c3.t[1] == Approx(1));
    CHECK(c3.t[2] == Approx(3));
    const auto c1 = solve_cubic(-2.0, 1.0, -2.0, 1.0);  // (t - 2)(t^2 + 1)
    REQUIRE(c1.count == 1);
    CHECK(c1.t[0] == Approx(2));
    const auto cd = solve_cubic(-3.0, 7.0, -5.0, 1.0);  // (t - 1)^2 (t - 3)
    REQUIRE(cd.count == 3);
    CHECK(cd.t[0] == Approx(1).epsilon(1e-7));
    CHECK(cd.t[1] == Approx(1).epsilon(1e-7));
    CHECK(cd.t[2] == Approx(3));
    const auto ct = solve_cubic(-8.0, 12.0, -6.0, 1.0);  // (t - 2)^3
    REQUIRE(ct.count >= 1);
    for (std::size_t i = 0; i < ct.count; ++i) {
        CHECK(ct.t[i] == Approx(2).epsilon(1e-5));
    }
}

TEST_CASE("closed-form quartic", "[intersect][roots]") {
    SECTION("four distinct roots") {
        const auto p = from_roots(-2.5, -0.25, 1.0, 4.0);
        const auto r = solve_closed_form(p);
        REQUIRE(r.count == 4);
        CHECK(r.t[0] == Approx(-2.5));
        CHECK(r.t[1] == Approx(-0.25));
        CHECK(r.t[2] == Approx(1));
        CHECK(r.t[3] == Approx(4));
    }
    SECTION("double root (t - 1)^2 (t - 3)(t + 2)") {
        const auto r = solve_quartic(-6.0, 11.0, -3.0, -3.0, 1.0);
        REQUIRE(r.count == 4);
        CHECK(r.t[0] == Approx(-2));
        CHECK(r.t[1] == Approx(1).epsilon(1e-7));  // a double root is defined to ~sqrt(eps)
        CHECK(r.t[2] == Approx(1).epsilon(1e-7));
        CHECK(r.t[3] == Approx(3));
    }
    SECTION("biquadratic and no real roots") {
        const auto b = solve_closed_form(from_roots(-2, -1, 1, 2));
        REQUIRE(b.count == 4);
        CHECK(b.t[0] == Approx(-2));
        CHECK(b.t[3] == Approx(2));
        CHECK(solve_quartic(5.0, 0.0, 3.0, 0.0, 1.0).count == 0);  // t^4 + 3 t^2 + 5 > 0
    }
    SECTION("degenerate leading coefficients give lower degrees and no NaN") {
        const auto r = solve_quartic(-6.0, 1.0, 1.0, 0.0, 0.0);
        REQUIRE(r.count == 2);
        CHECK(r.t[0] == Approx(-3));
        CHECK(solve_quartic(0.0, 0.0, 0.0, 0.0, 0.0).count == 0);
        CHECK(solve_quartic(1.0, 0.0, 0.0, 0.0, 0.0).count == 0);
        const auto f = solve_quartic(-1.0f, 0.0f, 0.0f, 0.0f, 1.0f);
        REQUIRE(f.count == 2);
        for (std::size_t i = 0; i < f.count; ++i) {
            CHECK(std::isfinite(f.t[i]));
        }
    }
    SECTION("random quartics with four real roots") {
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(-10, 10);
        for (int i = 0; i < 500; ++i) {
            std::array<double, 4> rs{u(rng), u(rng), u(rng), u(rng)};
            std::sort(rs.begin(), rs.end());
            if (rs[1] - rs[0] < 0.1 || rs[2] - rs[1] < 0.1 || rs[3] - rs[2] < 0.1) {
                continue;
            }
            const auto r = solve_closed_form(from_roots(rs[0], rs[1], rs[2], rs[3]));
            REQUIRE(r.count == 4);
            for (std::size_t k = 0; k < 4; ++k) {
                CHECK(r.t[k] == Approx(rs[k]).margin(1e-9));
            }
        }
    }
}

TEST_CASE("Newton with bisection safeguard", "[intersect][roots]") {
    const auto p = from_roots(-2.5, -0.25, 1.0, 4.0);
    const auto fdf = [&](double t) {
        double v, d;
        p.eval(t, v, d);
        return std::pair<double, double>{v, d};
    };
    const auto r = newton_bisect(fdf, 0.5, 2.0);
    REQUIRE(r);
    CHECK(*r == Approx(1).epsilon(1e-14));
    const auto r2 = newton_bisect(fdf, 2.0, 10.0);  // wide bracket: bisection fallback needed
    REQUIRE(r2);
    CHECK(*r2 == Approx(4).epsilon(1e-14));
    CHECK_FALSE(newton_bisect(fdf, 1.5, 3.0));  // no sign change
    const auto num =
        newton_bisect(numeric_derivative<double>([&](double t) { return p(t); }), -3.0, -1.0);
    REQUIRE(num);
    CHECK(*num == Approx(-2.5).epsilon(1e-12));
    const auto cosine =
        newton_bisect(numeric_derivative<float>([](float t) { return std::cos(t); }), 1.0f, 2.0f);
    REQUIRE(cosine);
    CHECK(*cosine == Approx(1.5707963).epsilon(1e-6));
}

TEST_CASE("Laguerre finds all roots", "[intersect][roots]") {
    SECTION("quartic with four distinct real roots") {
        const auto r = laguerre_real_roots(from_roots(-2.5, -0.25, 1.0, 4.0));
        REQUIRE(r.count == 4);
        CHECK(r.t[0] == Approx(-2.5).epsilon(1e-12));
        CHECK(r.t[1] == Approx(-0.25).epsilon(1e-12));
        CHECK(r.t[2] == Approx(1).epsilon(1e-12));
        CHECK(r.t[3] == Approx(4).epsilon(1e-12));
    }
    SECTION("complex pair and two real roots") {
        // (t^2 + 1)(t - 2)(t + 0.5) = t^4 - 1.5 t^3 + 0 t^2 - 1.5 t - 1
        Polynomial<double, 4> p{{-1, -1.5, 0, -1.5, 1}};
        std::size_t n = 0;
        const auto all = laguerre_all_roots(p, n);
        REQUIRE(n == 4);
        int complex_count = 0;
        for (std::size_t i = 0; i < n; ++i) {
            CHECK(std::abs(p.c[4] * std::pow(all[i], 4) + p.c[3] * std::pow(all[i], 3) +
                           p.c[1] * all[i] + p.c[0]) < 1e-12);
            complex_count += std::abs(all[i].imag()) > 0.5 ? 1 : 0;
        }
        CHECK(complex_count == 2);
        const auto r = laguerre_real_roots(p);
        REQUIRE(r.count == 2);
        CHECK(r.t[0] == Approx(-0.5));
        CHECK(r.t[1] == Approx(2));
    }
    SECTION("degenerate leading coefficient and float") {
        const auto r = laguerre_real_roots(Polynomial<float, 4>{{-6.0f, 1.0f, 1.0f, 0.0f, 0.0f}});
        REQUIRE(r.count == 2);
        CHECK(r.t[0] == Approx(-3).epsilon(1e-5));
        CHECK(r.t[1] == Approx(2).epsilon(1e-5));
        CHECK(laguerre_real_roots(Polynomial<double, 4>{}).count == 0);
    }
    SECTION("agrees with the closed form on random quartics") {
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-5, 5);
        for (int i = 0; i < 300; ++i) {
            const Polynomial<double, 4> p{{u(rng), u(rng), u(rng), u(rng), u(rng)}};
            const auto a = laguerre_real_roots(p);
            const auto b = solve_closed_form(p);
            // Compare only well-separated cases (a near-double root may go either way).
            bool separated = true;
            for (std::size_t k = 0; k + 1 < b.count; ++k) {
                separated = separated && b.t[k + 1] - b.t[k] > 1e-3;
            }
            if (!separated) {
                continue;
            }
            REQUIRE(a.count == b.count);
            for (std::size_t k = 0; k < a.count; ++k) {
                CHECK(a.t[k] == Approx(b.t[k]).margin(1e-8));
            }
        }
    }
}
