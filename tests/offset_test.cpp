// Offset policies for secondary-ray origins: the ULP offset moves every coordinate to the side of
// the normal by a distance that scales with |p|, the fixed epsilon does not.
#include "trace/offset.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace rtlab;

TEST_CASE("offset policies parse and print", "[trace][offset]") {
    for (OffsetPolicy p : {OffsetPolicy::none, OffsetPolicy::epsilon, OffsetPolicy::ulp}) {
        CHECK(parse_offset_policy(to_string(p)) == p);
    }
    CHECK_THROWS_AS(parse_offset_policy("ulps"), std::invalid_argument);
}

TEMPLATE_TEST_CASE("the ULP offset lands on the normal's side at every scale",
                   "[trace][offset]",
                   float,
                   double) {
    using T = TestType;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> exponent(-6, 8), unit(-1, 1);
    for (int i = 0; i < 20000; ++i) {
        const auto mag = [&] { return std::pow(10.0, exponent(rng)) * unit(rng); };
        const Vec3<T> p{static_cast<T>(mag()), static_cast<T>(mag()), static_cast<T>(mag())};
        Vec3d nd{unit(rng), unit(rng), unit(rng)};
        if (length(nd) < 1e-3) {
            continue;
        }
        const Vec3<T> n(normalize(nd));
        const Vec3<T> q = offset_origin(p, n, OffsetPolicy::ulp, T(0));
        for (std::size_t k = 0; k < 3; ++k) {
            const double moved = static_cast<double>(q[k]) - static_cast<double>(p[k]);
            // Each coordinate moves with the sign of n's component (or stays when it is ~0),
            // and never by more than 257 ULPs of |p| or the fixed near-origin step.
            CHECK(moved * static_cast<double>(n[k]) >= 0);
            const double ulp = std::abs(
                static_cast<double>(std::nextafter(p[k], std::numeric_limits<T>::infinity())) -
                static_cast<double>(p[k]));
            CHECK(std::abs(moved) <= 257 * ulp + 1.0 / 65536);
        }
        CHECK(offset_origin(p, n, OffsetPolicy::none, T(1)) == p);
    }
    // Along an axis the ULP offset is exactly 256 ULPs away from the origin band.
    const Vec3<T> far{T(1000), T(-1000), T(0.5)};
    const Vec3<T> q = offset_origin(far, Vec3<T>{1, 0, 0}, OffsetPolicy::ulp, T(0));
    T expect = far.x;
    for (int k = 0; k < 256; ++k) {
        expect = std::nextafter(expect, std::numeric_limits<T>::infinity());
    }
    CHECK(q.x == expect);
    CHECK(q.y == far.y);
    CHECK(q.z == far.z);
    const Vec3<T> down = offset_origin(far, Vec3<T>{0, -1, 0}, OffsetPolicy::ulp, T(0));
    CHECK(down.y < far.y);
    const Vec3<T> eps = offset_origin(far, Vec3<T>{0, 0, 1}, OffsetPolicy::epsilon, T(0.25));
    CHECK(eps.z == T(0.75));
}
