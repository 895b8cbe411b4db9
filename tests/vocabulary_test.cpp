// Vec3, Ray, Bounds3 and Hit: the invariants everything else relies on.
#include "intersect/bounds.h"
#include "intersect/hit.h"
#include "intersect/ray.h"
#include "intersect/vec.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace rtlab;

TEST_CASE("vector algebra", "[intersect][vocabulary]") {
    const Vec3d a{1, 2, 3}, b{-4, 5, 0.5};
    CHECK(dot(a, b) == Approx(1 * -4 + 2 * 5 + 3 * 0.5));
    const Vec3d c = cross(a, b);
    CHECK(dot(c, a) == Approx(0).margin(1e-12));
    CHECK(dot(c, b) == Approx(0).margin(1e-12));
    CHECK(length(normalize(b)) == Approx(1));
    CHECK(max_abs_axis(Vec3f{-7, 3, 6}) == 0);
    CHECK(max_abs_axis(Vec3f{0, 0, -1}) == 2);
    CHECK(Vec3d(Vec3f{0.1f, 0, 0}).x == static_cast<double>(0.1f));
}

TEST_CASE("bounds start empty and grow", "[intersect][vocabulary]") {
    Bounds3f b;
    CHECK(b.empty());
    CHECK(b.surface_area() == 0);
    b.extend(Vec3f{1, 2, 3});
    CHECK_FALSE(b.empty());
    CHECK(b.surface_area() == 0);
    b.extend(Bounds3f{{0, 0, 0}, {2, 2, 2}});
    CHECK(b == Bounds3f{{0, 0, 0}, {2, 2, 3}});
    CHECK(b.surface_area() == Approx(2 * (4 + 6 + 6)));
    CHECK(b.largest_axis() == 2);
    CHECK(b.contains(Vec3f{2, 2, 3}));
    CHECK_FALSE(b.contains(Vec3f{2, 2, 3.001f}));
    CHECK(intersection(b, Bounds3f{{5, 5, 5}, {6, 6, 6}}).empty());
}

TEST_CASE("ray validity rejects what traversal must never see", "[intersect][vocabulary]") {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(is_valid(Rayf{{0, 0, 0}, {0, 0, 1}}));
    CHECK(is_valid(Rayf{{0, 0, 0}, {1, 1e-40f, 0}}));        // a denormal component is fine
    CHECK(is_valid(Rayf{{0, 0, 0}, {1e-20f, 0, 0}}));        // tiny, but 1/d is finite
    CHECK_FALSE(is_valid(Rayf{{0, 0, 0}, {1e-40f, 0, 0}}));  // 1/d overflows: rejected
    CHECK_FALSE(is_valid(Rayf{{0, 0, 0}, {0, 0, 0}}));
    CHECK_FALSE(is_valid(Rayf{{nan, 0, 0}, {0, 0, 1}}));
    CHECK_FALSE(is_valid(Rayf{{0, 0, 0}, {inf, 0, 1}}));
    CHECK_FALSE(is_valid(Rayf{{0, 0, 0}, {0, 0, 1}, 2, 1}));
    CHECK_FALSE(is_valid(Rayf{{0, 0, 0}, {0, 0, 1}, nan, 1}));
    CHECK(Rayf{{1, 2, 3}, {0, 0, 2}}.at(1.5f) == Vec3f{1, 2, 6});
}

TEST_CASE("hits start empty", "[intersect][vocabulary]") {
    const Hit h;
    CHECK_FALSE(h.valid());
    CHECK(std::isinf(h.t));
}
