// Cone methods: analytic roots on cylinders, pointed and truncated cones (side, caps, windows,
// inside origins, rays along the axis and along a generator), normals, bounds, and the precision
// of the stable method on small far cones.
#include "intersect/cone/methods.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtlab;

namespace {

/// Cylinder of radius 1 about the z axis, z in [0, 2].
template <class T>
Cone<T> cylinder(ConeCaps caps = ConeCaps::none) {
    return {{T(0), T(0), T(0)}, T(1), {T(0), T(0), T(2)}, T(1), caps};
}

/// Pointed cone: base radius 1 at z = 0, apex (radius 0) at z = 1.
template <class T>
Cone<T> pointed(ConeCaps caps = ConeCaps::none) {
    return {{T(0), T(0), T(0)}, T(1), {T(0), T(0), T(1)}, T(0), caps};
}

template <class M>
std::optional<PrimHit<typename M::Scalar>> hit(const Cone<typename M::Scalar>& c,
                                               const Ray<typename M::Scalar>& r) {
    return M::intersect(M::prepare(c), r);
}

}  // namespace

TEMPLATE_TEST_CASE("cone methods: analytic roots, caps and windows",
                   "[intersect][cone]",
                   ConeQuadric<float>,
                   ConeStable<float>,
                   ConeQuadric<double>,
                   ConeStable<double>) {
    using T = typename TestType::Scalar;
    using R = Ray<T>;
    SECTION("cylinder side from outside, non-unit direction") {
        const R ray{{T(-5), T(0), T(1)}, {T(2), T(0), T(0)}};  // enters at x = -1: t = 2
        const auto h = hit<TestType>(cylinder<T>(), ray);
        REQUIRE(h);
        CHECK(h->t == Approx(2));
        CHECK(h->u == 0);
        CHECK(h->v == Approx(0.5));
        CHECK(TestType::occluded(TestType::prepare(cylinder<T>()), ray));
    }
    SECTION("origin inside reports the leaving root") {
        const R ray{{T(0), T(0.5), T(1)}, {T(0), T(1), T(0)}};
        const auto h = hit<TestType>(cylinder<T>(), ray);
        REQUIRE(h);
        CHECK(h->t == Approx(0.5));
    }
    SECTION("open ends: a ray along the axis misses; caps catch it") {
        const R ray{{T(0), T(0.25), T(-5)}, {T(0), T(0), T(1)}};
        CHECK_FALSE(hit<TestType>(cylinder<T>(), ray));
        const auto base = hit<TestType>(cylinder<T>(ConeCaps::base), ray);
        REQUIRE(base);
        CHECK(base->t == Approx(5));
        CHECK(base->u == 1);
        const auto apex = hit<TestType>(cylinder<T>(ConeCaps::apex), ray);
        REQUIRE(apex);
        CHECK(apex->t == Approx(7));
        CHECK(apex->u == 2);
        const auto both = hit<TestType>(cylinder<T>(ConeCaps::both), ray);
        REQUIRE(both);
        CHECK(both->t == Approx(5));
    }
    SECTION("a ray through an open end hits the inside of the side") {
        // From above the top, slanted: enters the top opening, meets the wall at x = 1.
        const R ray{{T(0), T(0), T(3)}, {T(1), T(0), T(-1)}};
        const auto h = hit<TestType>(cylinder<T>(), ray);
        REQUIRE(h);
        CHECK(h->t == Approx(1));
        CHECK(h->v == Approx(1));
    }
    SECTION("segment beyond the ends misses") {
        const R ray{{T(-5), T(0), T(2.5)}, {T(1), T(0), T(0)}};
        CHECK_FALSE(hit<TestType>(cylinder<T>(), ray));
        CHECK_FALSE(hit<TestType>(pointed<T>(), ray));
    }
    SECTION("pointed cone: side at half height, and the mirrored nappe is not part of it") {
        const R ray{{T(-5), T(0), T(0.5)}, {T(1), T(0), T(0)}};  // radius 0.5 at z = 0.5
        const auto h = hit<TestType>(pointed<T>(), ray);
        REQUIRE(h);
        CHECK(h->t == Approx(4.5));
        CHECK(h->v == Approx(0.5));
        // z = 1.5 meets the double cone's other nappe (radius 0.5) but not this cone.
        const R above{{T(-5), T(0), T(1.5)}, {T(1), T(0), T(0)}};
        CHECK_FALSE(hit<TestType>(pointed<T>(), above));
    }
    SECTION("a ray parallel to a generator has one root") {
        // Points (-t, 0.5, t): radius 1 - t equals sqrt(t^2 + 0.25) at t = 0.375.
        const R ray{{T(0), T(0.5), T(0)}, {T(-1), T(0), T(1)}};
        const auto h = hit<TestType>(pointed<T>(), ray);
        REQUIRE(h);
        CHECK(h->t == Approx(0.375));
    }
    SECTION("truncated cone with base cap, from below") {
        const Cone<T> c{{T(1), T(1), T(1)}, T(2), {T(1), T(1), T(3)}, T(1), ConeCaps::base};
        const R ray{{T(2), T(1), T(-4)}, {T(0), T(0), T(1)}};
        const auto h = hit<TestType>(c, ray);
        REQUIRE(h);
        CHECK(h->t == Approx(5));
        CHECK(h->u == 1);
        // Without the cap the ray (radius 1 from the axis) meets the side where r(z) = 1: z = 3.
        const Cone<T> open{c.base, c.base_radius, c.apex, c.apex_radius, ConeCaps::none};
        const auto side = hit<TestType>(open, ray);
        REQUIRE(side);
        CHECK(side->t == Approx(7));
    }
    SECTION("window [tmin, tmax]") {
        R ray{{T(-5), T(0), T(1)}, {T(1), T(0), T(0)}};  // roots 4 and 6
        ray.tmax = T(3.5);
        CHECK_FALSE(hit<TestType>(cylinder<T>(), ray));
        CHECK_FALSE(TestType::occluded(TestType::prepare(cylinder<T>()), ray));
        ray.tmin = T(4.5);
        ray.tmax = T(10);
        REQUIRE(hit<TestType>(cylinder<T>(), ray));
        CHECK(hit<TestType>(cylinder<T>(), ray)->t == Approx(6));
        ray.tmin = T(-100);
        ray.org.x = T(5);
        REQUIRE(hit<TestType>(cylinder<T>(), ray));
        CHECK(hit<TestType>(cylinder<T>(), ray)->t == Approx(-6));
    }
    SECTION("axis-aligned rays in every direction, any cone orientation") {
        for (std::size_t axis = 0; axis < 3; ++axis) {
            // Cylinder of radius 1 along `axis` from 0 to 2; ray along the next axis.
            Cone<T> c = cylinder<T>();
            c.apex = {T(0), T(0), T(0)};
            c.apex[axis] = T(2);
            const std::size_t across = (axis + 1) % 3;
            R ray{{T(0), T(0), T(0)}, {T(0), T(0), T(0)}};
            ray.org[axis] = T(1.5);
            ray.org[across] = T(-4);
            ray.dir[across] = T(0.5);
            const auto h = hit<TestType>(c, ray);
            REQUIRE(h);
            CHECK(h->t == Approx(6));
        }
    }
    SECTION("bounds contain the end disks and are tight for axis-aligned cones") {
        const auto p = TestType::prepare(cylinder<T>());
        const Bounds3<T> b = TestType::bounds(p);
        CHECK(b.contains(Vec3<T>{T(1), T(0), T(2)}));
        CHECK(b.contains(Vec3<T>{T(0), T(-1), T(0)}));
        CHECK(b.hi.x < T(1.0001));
        CHECK(b.lo.z > T(-0.0001));
    }
}

TEST_CASE("cone normals: outward on the side, along the axis on caps", "[intersect][cone]") {
    const auto p = detail::prepare_cone(pointed<double>(ConeCaps::base));
    // Side point (0.5, 0, 0.5): radial +x tilted up by the slope -1: (1, 0, 1).
    const Vec3d n = cone_normal(p, Vec3d{0.5, 0, 0.5});
    CHECK(n.x == Approx(1));
    CHECK(n.z == Approx(1));
    CHECK(std::abs(n.y) < 1e-12);
    const Vec3d cap = cone_normal(p, Vec3d{0.2, 0.1, 0});
    CHECK(cap == Vec3d{0, 0, -1});
    // Open cone: the same point gets the side's normal.
    const auto open = detail::prepare_cone(pointed<double>());
    CHECK(cone_normal(open, Vec3d{0.99, 0, 0.01}).x > 0.5);
}

TEST_CASE("cone methods agree with each other on random rays", "[intersect][cone][property]") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::size_t hits = 0;
    for (int i = 0; i < 2000; ++i) {
        Coned c;
        c.base = {u(rng), u(rng), u(rng)};
        c.apex = c.base + Vec3d{u(rng), u(rng), u(rng)};
        c.base_radius = 0.1 + 0.4 * std::abs(u(rng));
        c.apex_radius = i % 3 == 0 ? c.base_radius : (i % 3 == 1 ? 0.0 : 0.5 * std::abs(u(rng)));
        c.caps = static_cast<ConeCaps>(i % 4);
        // Aimed at a point within about a radius of the axis.
        const Vec3d org{3 * u(rng), 3 * u(rng), 3 * u(rng)};
        const Vec3d aim = c.base + (c.apex - c.base) * (0.5 + 0.6 * u(rng)) +
                          Vec3d{u(rng), u(rng), u(rng)} * (0.5 * c.base_radius);
        const Rayd ray{org, aim - org};
        const auto a = ConeQuadric<double>::intersect(ConeQuadric<double>::prepare(c), ray);
        const auto b = ConeStable<double>::intersect(ConeStable<double>::prepare(c), ray);
        REQUIRE(a.has_value() == b.has_value());
        if (a) {
            ++hits;
            CHECK(a->t == Approx(b->t).epsilon(1e-9));
            CHECK(a->u == b->u);
        }
    }
    CHECK(hits > 200);
}

TEST_CASE("small far cones: the stable method beats the closed form in float",
          "[intersect][cone]") {
    // A cylinder of radius 1e-3 at distance 1e3 (D/r = 1e6), rays aimed within half the radius
    // of its axis; the double stable method is the reference.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> off(-0.5e-3, 0.5e-3);
    const Conef c{{0.3f, -0.2f, 1000}, 1e-3f, {0.3f, 0.8f, 1000}, 1e-3f, ConeCaps::none};
    const Coned cd{Vec3d(c.base), static_cast<double>(c.base_radius), Vec3d(c.apex),
                   static_cast<double>(c.apex_radius), ConeCaps::none};
    double worst_q = 0, worst_s = 0;
    for (int i = 0; i < 200; ++i) {
        const Rayf ray{
            {0, 0, 0},
            {static_cast<float>(0.3 + off(rng)), 0.1f, static_cast<float>(1000 + off(rng))}};
        const auto ref = ConeStable<double>::intersect(ConeStable<double>::prepare(cd), Rayd(ray));
        REQUIRE(ref);
        const auto q = ConeQuadric<float>::intersect(ConeQuadric<float>::prepare(c), ray);
        const auto s = ConeStable<float>::intersect(ConeStable<float>::prepare(c), ray);
        REQUIRE(s);
        const auto err = [&](double t) { return std::abs(t - ref->t) / ref->t; };
        worst_s = std::max(worst_s, err(s->t));
        worst_q = q ? std::max(worst_q, err(q->t)) : 1.0;
    }
    CHECK(worst_s < 1e-5);
    CHECK(worst_s < worst_q);
}
