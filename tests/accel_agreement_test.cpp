// Every registry entry against the brute-force oracle: closest hit, any hit, validate(),
// determinism and robust traversal, on seeded primitive soups of several sizes.

#include "accel/any_accel.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <concepts>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab {
namespace {

/// True when both hold the same structure type and compare equal (structures without == are
/// reported equal, so this only checks those that can be compared).
bool same_structure(const AnyAccel& a, const AnyAccel& b) {
    if (a.index() != b.index()) {
        return false;
    }
    return visit_accel(a, [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::equality_comparable<T>) {
            return s == std::get<T>(b);
        } else {
            return true;
        }
    });
}

/// Builds every registered structure on soup, requires it to be valid and checks it against the
/// oracle's answers on rays.
void check_every_structure(const test::Soup& soup, const std::vector<Rayf>& rays) {
    const std::vector<test::OracleAnswer> expected = test::oracle_answers(soup, rays);
    for (const AccelEntry& entry : accel_registry()) {
        CAPTURE(entry.name);
        const AnyAccel accel = build_accel(default_spec(entry), soup.input());
        REQUIRE(accel_validate(accel).empty());
        visit_accel(
            accel, [&](const auto& s) { test::check_agrees_with_oracle(s, soup, rays, expected); });
    }
}

}  // namespace

TEST_CASE("every registered structure agrees with brute force", "[accel][agreement]") {
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const auto count = GENERATE(1u, 2u, 17u, 500u);
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(static_cast<int>(kind), count, seed);
    const test::Soup soup = test::random_soup(kind, seed, count);
    const std::vector<Rayf> rays = test::random_rays(soup, seed, count >= 500 ? 400 : 200);
    const std::vector<test::OracleAnswer> expected = test::oracle_answers(soup, rays);

    for (const AccelEntry& entry : accel_registry()) {
        for (const AccelSpec& spec : test::default_and_varied_specs(entry)) {
            CAPTURE(spec.canonical());
            const AnyAccel accel = build_accel(spec, soup.input());
            REQUIRE(accel_validate(accel).empty());
            REQUIRE(same_structure(accel, build_accel(spec, soup.input())));
            visit_accel(accel, [&](const auto& s) {
                test::check_agrees_with_oracle(s, soup, rays, expected);
            });
        }
    }
}

TEST_CASE("structures agree on duplicate, zero-size and unusable primitives",
          "[accel][agreement]") {
    // 40 copies of one box, 30 point boxes at one spot, flat boxes, and boxes that fail
    // is_usable_box (empty, NaN, infinite, half-infinite), which must never be offered.
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    test::Soup soup;
    for (int i = 0; i < 40; ++i) {
        soup.boxes.push_back({{0.2f, 0.2f, 0.2f}, {0.6f, 0.5f, 0.4f}});
    }
    for (int i = 0; i < 30; ++i) {
        soup.boxes.push_back(Bounds3f(Vec3f{0.5f, 0.5f, 0.5f}));
    }
    for (int i = 0; i < 20; ++i) {
        const float x = 0.05f * static_cast<float>(i);
        soup.boxes.push_back({{x, 0, 0}, {x, 1, 1}});
    }
    const std::vector<Bounds3f> unusable{
        Bounds3f{},
        {{0, 0, 0}, {nan, 1, 1}},
        {{-inf, -inf, -inf}, {inf, inf, inf}},
        {{0, 0, 0}, {inf, 1, 1}},
        {{-inf, 0.2f, 0.2f}, {0.5f, 0.3f, 0.3f}},
    };
    const auto first_unusable = static_cast<std::uint32_t>(soup.boxes.size());
    soup.boxes.insert(soup.boxes.end(), unusable.begin(), unusable.end());
    for (const Bounds3f& b : unusable) {
        CHECK_FALSE(is_usable_box(b));
    }
    const std::vector<Rayf> rays = test::random_rays(soup, 7, 400);
    check_every_structure(soup, rays);

    // One rule for every structure: no unusable primitive is ever offered to a leaf callback.
    for (const AccelEntry& entry : accel_registry()) {
        CAPTURE(entry.name);
        const AnyAccel accel = build_accel(default_spec(entry), soup.input());
        std::uint32_t offered_unusable = 0;
        const auto record = [&](std::uint32_t id, const Rayf&) {
            offered_unusable += id >= first_unusable ? 1u : 0u;
            return false;
        };
        visit_accel(accel, [&](const auto& s) {
            for (const Rayf& ray : rays) {
                s.occluded(ray, record);
                s.template occluded<true>(ray, record);
            }
        });
        CHECK(offered_unusable == 0);
    }
}

TEST_CASE("invalid rays are rejected by every structure", "[accel][agreement]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 3, 100);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const Rayf bad[] = {
        {{nan, 0.5f, 0.5f}, {1, 0, 0}},        {{-1, 0.5f, 0.5f}, {nan, 0, 0}},
        {{-1, 0.5f, 0.5f}, {0, 0, 0}},         {{-1, 0.5f, 0.5f}, {1, 0, 0}, nan, 10},
        {{-1, 0.5f, 0.5f}, {1, 0, 0}, 0, nan}, {{-1, 0.5f, 0.5f}, {1, 0, 0}, 2, 1},
        {{-inf, 0.5f, 0.5f}, {1, 0, 0}},
    };
    for (const AccelEntry& entry : accel_registry()) {
        CAPTURE(entry.name);
        const AnyAccel accel = build_accel(default_spec(entry), soup.input());
        visit_accel(accel, [&](const auto& s) {
            for (const Rayf& ray : bad) {
                const TraversalStats st = test::check_no_hit(s, soup, ray);
                CHECK(st.nodes == 0);
                CHECK(st.prims == 0);
            }
        });
    }
}

TEST_CASE("SAH BVHs visit far fewer boxes than brute force", "[accel][agreement]") {
    // Brute force tests all 500 boxes per ray; a BVH tests O(log N) node boxes. (Primitive
    // counts are not compared: brute force offers only primitives whose own box the window
    // meets, a BVH every primitive of a leaf it opens.)
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 11, 500);
    const std::vector<Rayf> rays = test::random_rays(soup, 11, 400);
    auto count = [&](std::string_view name) {
        const AnyAccel accel = build_accel(name, soup.input());
        return visit_accel(accel,
                           [&](const auto& s) { return test::closest_hit_stats(s, soup, rays); });
    };
    const TraversalStats brute = count("brute");
    // Each row with its default leaf bound (8 for the SAH rows).
    const std::pair<std::string_view, std::uint64_t> rows[] = {
        {"bvh:binned", 8}, {"bvh:sweep", 8}, {"bvh4", 8}, {"bvh8", 8}, {"bvh16", 8}};
    for (const auto& [name, max_leaf] : rows) {
        CAPTURE(name);
        const TraversalStats st = count(name);
        CHECK(st.rays == brute.rays);
        CHECK(st.nodes * 4 < brute.nodes);
        CHECK(st.prims < 3 * max_leaf * st.rays);  // about three leaves per ray at most
    }
}

TEST_CASE("build_accel names the known structures on a typo", "[accel][registry]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 1, 10);
    CHECK(find_accel("bvh:sweep") != nullptr);
    CHECK(find_accel("bvh:nope") == nullptr);
    CHECK_THROWS_WITH(build_accel("bvh:nope", soup.input()),
                      Catch::Contains("bvh:binned") && Catch::Contains("brute"));
    for (const AccelEntry& e : accel_registry()) {
        CHECK(!e.description.empty());
        CHECK(find_accel(e.name) == &e);
    }
}

TEST_CASE("every structure agrees with brute force on 100,000 primitives",
          "[accel][agreement][.slow]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 5, 100000);
    const std::vector<Rayf> rays = test::random_rays(soup, 5, 48);
    check_every_structure(soup, rays);
}

}  // namespace rtlab
