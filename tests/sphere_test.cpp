// Sphere methods: analytic roots, windows, inside origins, tangency, and the precision of the
// stable method on small far spheres.
#include "intersect/sphere/methods.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtlab;

namespace {

/// Relative error of the near root t for a sphere of radius r at distance dist straight ahead
/// (exact near root dist - r), over rays slightly off the centre line.
template <class M>
double worst_far_error(double dist, double r) {
    using T = typename M::Scalar;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> off(-0.5, 0.5);
    const auto p = M::prepare({{T(0), T(0), static_cast<T>(dist)}, static_cast<T>(r)});
    double worst = 0;
    for (int i = 0; i < 200; ++i) {
        // Aim at a point within half the radius of the centre; the exact t comes in double from
        // the float inputs (the double quadratic is far more accurate than float here).
        const Vec3<T> dir{static_cast<T>(off(rng) * r), static_cast<T>(off(rng) * r),
                          static_cast<T>(dist)};
        const Ray<T> ray{{0, 0, 0}, dir};
        const Vec3d d(dir), c(p.center);
        const double a = dot(d, d), h = -dot(c, d);
        const Vec3d fp = -c - d * (h / a);
        const double disc = a * (static_cast<double>(p.radius2) - dot(fp, fp));
        const double q = -(h + std::copysign(std::sqrt(disc), h));
        const double exact = std::min(q / a, (dot(c, c) - static_cast<double>(p.radius2)) / q);
        const auto hit = M::intersect(p, ray);
        if (!hit) {
            return 1.0;
        }
        worst = std::max(worst, std::abs(static_cast<double>(hit->t) - exact) / exact);
    }
    return worst;
}

}  // namespace

TEMPLATE_TEST_CASE("sphere methods: analytic roots and windows",
                   "[intersect][sphere]",
                   SphereGeometric<float>,
                   SphereAlgebraic<float>,
                   SphereStable<float>,
                   SphereGeometric<double>,
                   SphereAlgebraic<double>,
                   SphereStable<double>) {
    using T = typename TestType::Scalar;
    const auto p = TestType::prepare({{T(1), T(2), T(3)}, T(2)});
    SECTION("entering and leaving roots, non-unit direction") {
        const Ray<T> ray{{T(1), T(2), T(-7)}, {T(0), T(0), T(2)}};  // |d| = 2: t halves
        const auto roots = TestType::roots(p, ray, TestType::precompute(ray));
        REQUIRE(roots);
        CHECK(roots->first == Approx(4));
        CHECK(roots->second == Approx(6));
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        CHECK(hit->t == Approx(4));
        CHECK(hit->u == 0);
        CHECK(TestType::occluded(p, ray));
    }
    SECTION("origin inside reports the leaving root") {
        const Ray<T> ray{{T(1), T(2), T(3)}, {T(1), T(0), T(0)}};
        const auto hit = TestType::intersect(p, ray);
        REQUIRE(hit);
        CHECK(hit->t == Approx(2));
    }
    SECTION("window [tmin, tmax]") {
        Ray<T> ray{{T(1), T(2), T(-7)}, {T(0), T(0), T(1)}};  // roots 8 and 12
        ray.tmax = T(7.5);
        CHECK_FALSE(TestType::intersect(p, ray));
        CHECK_FALSE(TestType::occluded(p, ray));
        ray.tmax = T(10);
        ray.tmin = T(9);
        CHECK_FALSE(TestType::intersect(p, ray));
        ray.tmax = T(12);
        REQUIRE(TestType::intersect(p, ray));
        CHECK(TestType::intersect(p, ray)->t == Approx(12));
        ray.tmin = T(-100);  // window behind the origin: the geometric early out must not fire
        ray.org.z = T(20);
        REQUIRE(TestType::intersect(p, ray));
        CHECK(TestType::intersect(p, ray)->t == Approx(-19));
    }
    SECTION("sphere behind the origin misses") {
        const Ray<T> ray{{T(1), T(2), T(10)}, {T(0), T(0), T(1)}};
        CHECK_FALSE(TestType::intersect(p, ray));
    }
    SECTION("tangent ray: exactly tangent hits once, slightly outside misses") {
        // Line x = 3 (= centre.x + r), y = 2: touches at t = 10 from z = -7.
        const Ray<T> touch{{T(3), T(2), T(-7)}, {T(0), T(0), T(1)}};
        const auto hit = TestType::intersect(p, touch);
        REQUIRE(hit);
        CHECK(hit->t == Approx(10));
        const Ray<T> off{{T(3.001), T(2), T(-7)}, {T(0), T(0), T(1)}};
        CHECK_FALSE(TestType::intersect(p, off));
    }
    SECTION("zero direction components and axis-aligned rays") {
        for (std::size_t axis = 0; axis < 3; ++axis) {
            Ray<T> ray{{T(1), T(2), T(3)}, {T(0), T(0), T(0)}};
            ray.org[axis] -= T(5);
            ray.dir[axis] = T(0.5);
            const auto hit = TestType::intersect(p, ray);
            REQUIRE(hit);
            CHECK(hit->t == Approx(6));
        }
    }
    SECTION("bounds contain the sphere") {
        const Bounds3<T> b = TestType::bounds(p);
        CHECK(b.lo.x <= T(-1));
        CHECK(b.hi.z >= T(5));
        CHECK(b.contains(Vec3<T>{T(1), T(4), T(3)}));
    }
}

TEST_CASE("sphere methods agree on easy random rays", "[intersect][sphere][property]") {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-4, 4);
    for (int i = 0; i < 2000; ++i) {
        const Sphere<double> s{{u(rng), u(rng), u(rng)},
                               static_cast<double>(std::abs(u(rng))) + 0.5};
        const Ray<double> ray{{u(rng) * 3, u(rng) * 3, u(rng) * 3}, {u(rng), u(rng), u(rng)}};
        const auto a = SphereGeometric<double>::intersect(SphereGeometric<double>::prepare(s), ray);
        const auto b = SphereAlgebraic<double>::intersect(SphereAlgebraic<double>::prepare(s), ray);
        const auto c = SphereStable<double>::intersect(SphereStable<double>::prepare(s), ray);
        const auto roots = SphereStable<double>::roots(SphereStable<double>::prepare(s), ray,
                                                       SphereStable<double>::precompute(ray));
        // Skip near-tangent rays, where rounding may legitimately flip the answer.
        if (roots && std::abs(roots->second - roots->first) < 1e-6) {
            continue;
        }
        REQUIRE(a.has_value() == c.has_value());
        REQUIRE(b.has_value() == c.has_value());
        if (c) {
            CHECK(a->t == Approx(c->t).epsilon(1e-9));
            CHECK(b->t == Approx(c->t).epsilon(1e-9));
        }
    }
}

TEST_CASE("small far spheres: the stable method beats the algebraic one in float",
          "[intersect][sphere][precision]") {
    // D / r = 1e4 .. 1e6, D = 1000. Measured (g++ 12, x86-64, 200 rays each): stable worst
    // relative error 5e-8 .. 7e-8 (half a float ulp of t); algebraic 1e-4, 1e-5, 1e-6 (about r/D:
    // the discriminant b^2 - 4ac cancels to noise, so the chord is lost). Bound 5e-7 (~4 ulps,
    // 7x margin) and "algebraic at least 10x worse".
    for (const double ratio : {1e4, 1e5, 1e6}) {
        CAPTURE(ratio);
        const double stable = worst_far_error<SphereStable<float>>(1000.0, 1000.0 / ratio);
        const double algebraic = worst_far_error<SphereAlgebraic<float>>(1000.0, 1000.0 / ratio);
        CHECK(stable < 5e-7);
        CHECK(algebraic > 10 * stable);
    }
}
