// The cross-check's agreement counts: a ray agrees only with the exact hit/miss and, for a hit, t
// within the precision's tolerance; a hit on another surface (t far off) or a NaN t is wrong_t.
#include "crosscheck/accumulator.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using rtlab::xcheck::Accumulator;
using rtlab::xcheck::Row;
using rtlab::xcheck::t_tolerance;

namespace {

Row row_of(const Accumulator& acc) {
    return acc.row("p", "m", "float", "all", 0.0);
}

}  // namespace

TEST_CASE("tolerances: float looser than double, both far below a surface gap",
          "[crosscheck][accumulator]") {
    STATIC_REQUIRE(t_tolerance<float>() > t_tolerance<double>());
    // Rounding of a near-double root (sqrt(eps)) is inside, another surface (~1) far outside.
    CHECK(t_tolerance<float>() >
          std::sqrt(static_cast<double>(std::numeric_limits<float>::epsilon())));
    CHECK(t_tolerance<double>() > std::sqrt(std::numeric_limits<double>::epsilon()));
    CHECK(t_tolerance<float>() < 1e-2);
}

TEST_CASE("a leak through a closed mesh that hits the far side is wrong_t, not agree",
          "[crosscheck][accumulator]") {
    Accumulator acc(t_tolerance<float>());
    acc.add(true, true, 2.0, 2.0 * (1 + 1e-7));  // rounding: agrees
    acc.add(true, true, 4.0, 2.0);               // entry missed, exit hit: another surface
    acc.add(false, false, 0.0, 0.0);             // both miss: agrees
    acc.add(true, false, 1.0, 0.0);              // false hit
    acc.add(false, true, 0.0, 1.0);              // false miss
    const Row r = row_of(acc);
    CHECK(r.rays == 5);
    CHECK(r.agree == 2);
    CHECK(r.wrong_t == 1);
    CHECK(r.false_hit == 1);
    CHECK(r.false_miss == 1);
    CHECK(r.agree + r.wrong_t + r.false_hit + r.false_miss == r.rays);
    CHECK(r.max_rel_t_err == Approx(1.0));
    CHECK(r.t_tol == t_tolerance<float>());
}

TEST_CASE("the tolerance is per precision", "[crosscheck][accumulator]") {
    // A relative error of 1e-5 is rounding in float but a wrong answer in double.
    Accumulator f(t_tolerance<float>()), d(t_tolerance<double>());
    f.add(true, true, 1.0 + 1e-5, 1.0);
    d.add(true, true, 1.0 + 1e-5, 1.0);
    CHECK(row_of(f).agree == 1);
    CHECK(row_of(d).wrong_t == 1);
    CHECK(row_of(d).agree == 0);
}

TEST_CASE("a NaN t is never agreement", "[crosscheck][accumulator]") {
    Accumulator acc(t_tolerance<double>());
    acc.add(true, true, std::numeric_limits<double>::quiet_NaN(), 3.0);
    const Row r = row_of(acc);
    CHECK(r.agree == 0);
    CHECK(r.wrong_t == 1);
    CHECK(std::isinf(r.max_rel_t_err));
}

TEST_CASE("hit/no-hit methods agree on hit/miss alone and report no t",
          "[crosscheck][accumulator]") {
    Accumulator acc(t_tolerance<float>(), false);
    acc.add(true, true, 0.0, 5.0);
    acc.add(false, false, 0.0, 0.0);
    Accumulator merged(t_tolerance<float>(), false);
    merged.merge(acc);
    merged.merge(acc);
    const Row r = row_of(merged);
    CHECK(r.agree == 4);
    CHECK(r.wrong_t == 0);
    CHECK_FALSE(r.has_t);
    CHECK(std::isnan(r.max_rel_t_err));
}
