// Implicit-surface methods: analytic torus hits, the hole, tangency, gradient normals, and
// agreement of closed form, Newton and Laguerre on random rays away from tangency.
#include "intersect/implicit/methods.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtlab;

TEMPLATE_TEST_CASE("torus: analytic hits",
                   "[intersect][implicit]",
                   (ImplicitClosedForm<Torus, float>),
                   (ImplicitNewton<Torus, float>),
                   (ImplicitLaguerre<Torus, float>),
                   (ImplicitClosedForm<Torus, double>),
                   (ImplicitNewton<Torus, double>),
                   (ImplicitLaguerre<Torus, double>)) {
    using T = typename TestType::Scalar;
    // Centre (1, 2, 3), R = 1, r = 0.25, axis z.
    const auto p = TestType::prepare({{T(1), T(2), T(3)}, T(1), T(0.25)});
    const double tol = std::is_same_v<T, float> ? 1e-5 : 1e-12;
    SECTION("perpendicular to the axis through the centre: outer wall first") {
        const Ray<T> ray{{T(-2), T(2), T(3)}, {T(1), T(0), T(0)}};
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        CHECK(hit->t == Approx(1.75).epsilon(tol));
        Ray<T> inner = ray;
        inner.tmin = T(2);  // past the first wall: the hole side of the tube at x = -0.75
        REQUIRE(TestType::intersect(p, inner));
        CHECK(TestType::intersect(p, inner)->t == Approx(2.25).epsilon(tol));
    }
    SECTION("parallel to the axis through the tube, non-unit direction") {
        const Ray<T> ray{{T(2), T(2), T(-1)}, {T(0), T(0), T(2)}};
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        CHECK(hit->t == Approx(1.875).epsilon(tol));  // z = 2.75
    }
    SECTION("along the axis through the hole misses") {
        const Ray<T> ray{{T(1), T(2), T(-5)}, {T(0), T(0), T(1)}};
        CHECK_FALSE(TestType::intersect(p, ray));
        CHECK_FALSE(TestType::occluded(p, ray));
    }
    SECTION("origin inside the tube reports the exit") {
        const Ray<T> ray{{T(2), T(2), T(3)}, {T(0), T(1), T(0)}};
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        // exit where (sqrt(1 + y^2) - 1)^2 = r^2: y = sqrt(1.25^2 - 1) = 0.75
        CHECK(hit->t == Approx(0.75).epsilon(tol));
    }
    SECTION("rays near the top tangent plane z = r") {
        // Below the top circle by 1e-3 r: hits near x = -1 relative to the centre.
        const Ray<T> below{{T(-2), T(2), T(3.25 - 0.00025)}, {T(1), T(0), T(0)}};
        const auto hit = TestType::intersect(p, below);
        REQUIRE(hit);
        CHECK(hit->t == Approx(2).epsilon(0.02));
        const Ray<T> above{{T(-2), T(2), T(3.25 + 0.00025)}, {T(1), T(0), T(0)}};
        CHECK_FALSE(TestType::intersect(p, above));
    }
    SECTION("window and misses") {
        Ray<T> ray{{T(-2), T(2), T(3)}, {T(1), T(0), T(0)}};
        ray.tmax = T(1.7);
        CHECK_FALSE(TestType::intersect(p, ray));
        const Ray<T> away{{T(-2), T(2), T(3)}, {T(-1), T(0), T(0)}};
        CHECK_FALSE(TestType::intersect(p, away));
        const Ray<T> above{{T(-2), T(2), T(4)}, {T(1), T(0), T(0)}};
        CHECK_FALSE(TestType::intersect(p, above));
    }
    SECTION("gradient normal: unit and pointing away from the tube centre") {
        const Ray<T> ray{{T(-2), T(2.3), T(3.1)}, {T(1), T(0.05), T(0)}};
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        const Vec3<T> n = TestType::normal(p, ray, *hit);
        CHECK(length(n) == Approx(1).epsilon(1e-5));
        const Vec3<T> q = ray.at(hit->t) - Vec3<T>{T(1), T(2), T(3)};
        const Vec3<T> ring = normalize(Vec3<T>{q.x, q.y, T(0)});  // tube centre, R = 1
        const Vec3<T> radial = normalize(q - ring);
        CHECK(dot(n, radial) == Approx(1).epsilon(1e-4));
        CHECK(dot(n, ray.dir) < T(0));  // entering
    }
}

namespace {

/// Random rays through the surface's box; rays whose polynomial has a near-double or nearly real
/// complex root (tangency within ~1e-2 of the window) are dropped.
template <template <class> class S>
void check_agreement(const S<double>& surface, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto pc = ImplicitClosedForm<S, double>::prepare(surface);
    const auto pn = ImplicitNewton<S, double>::prepare(surface);
    const auto pl = ImplicitLaguerre<S, double>::prepare(surface);
    const Bounds3d box = surface.bounds();
    int compared = 0, hits = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3d target = box.center() + box.diagonal() * Vec3d{u(rng), u(rng), u(rng)} * 0.5;
        const Vec3d org = box.center() + normalize(Vec3d{u(rng), u(rng), u(rng)}) * 8.0;
        const Ray<double> ray{org, target - org};
        double t0, t1;
        if (!clip_to_box(box, ray, t0, t1)) {
            continue;
        }
        const auto poly = surface.along(ray.at(t0), ray.dir * (t1 - t0));
        std::size_t n = 0;
        const auto roots = laguerre_all_roots(poly, n);
        bool near_tangent = false;
        for (std::size_t a = 0; a < n; ++a) {
            near_tangent =
                near_tangent || (roots[a].imag() != 0 && std::abs(roots[a].imag()) < 1e-2);
            for (std::size_t b = a + 1; b < n; ++b) {
                near_tangent = near_tangent || std::abs(roots[a] - roots[b]) < 1e-2;
            }
        }
        if (near_tangent) {
            continue;
        }
        const auto c = ImplicitClosedForm<S, double>::intersect(pc, ray);
        const auto nw = ImplicitNewton<S, double>::intersect(pn, ray);
        const auto l = ImplicitLaguerre<S, double>::intersect(pl, ray);
        ++compared;
        REQUIRE(c.has_value() == nw.has_value());
        REQUIRE(c.has_value() == l.has_value());
        if (c) {
            ++hits;
            CHECK(nw->t == Approx(c->t).epsilon(1e-10));
            CHECK(l->t == Approx(c->t).epsilon(1e-10));
            CHECK(std::abs(surface.value(ray.at(c->t))) < 1e-8 * length(ray.dir));
        }
    }
    CHECK(compared > 200);
    CHECK(hits > 50);
}

}  // namespace

TEST_CASE("implicit methods agree on random rays away from tangency",
          "[intersect][implicit][property]") {
    check_agreement<Torus>({{0.5, -1, 2}, 1.5, 0.5}, 5);
    check_agreement<TangleCube>({{1, 0, -1}, 0.8}, 6);
}

TEST_CASE("tangle cube: value, gradient and a hit on a lobe", "[intersect][implicit]") {
    const TangleCube<double> s{{0, 0, 0}, 1};
    // On the x axis (y = z = 0): x^4 - 5x^2 + 11.8 > 0 everywhere, so the ray misses.
    const Ray<double> axis{{-3, 0, 0}, {1, 0, 0}};
    CHECK_FALSE(ImplicitClosedForm<TangleCube, double>::intersect(
        ImplicitClosedForm<TangleCube, double>::prepare(s), axis));
    // At y = sqrt(2.5) (the lobe), x^4 - 5x^2 + 5.55 = 0: x^2 = (5 + sqrt(25 - 22.2)) / 2.
    const Ray<double> lobe{{-3, std::sqrt(2.5), 0}, {1, 0, 0}};
    const double x = -std::sqrt((5 + std::sqrt(25 - 4 * 5.55)) / 2);
    const auto h = ImplicitNewton<TangleCube, double>::intersect(
        ImplicitNewton<TangleCube, double>::prepare(s), lobe);
    REQUIRE(h);
    CHECK(h->t == Approx(x + 3).epsilon(1e-12));
    const Vec3d g = s.gradient({x, std::sqrt(2.5), 0});
    CHECK(g.x == Approx(4 * x * x * x - 10 * x));
    CHECK(g.y == Approx(0).margin(1e-12));
}
