// Structure specs: parsing, canonical form, the parameters' dependencies, one-line errors, and
// parameters that reach the builders (different max_leaf, different trees, both agreeing with
// brute force).

#include "accel/any_accel.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "support/registry_lists.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtlab {
namespace {

TEST_CASE("the default structure is a registry row", "[accel][spec]") {
    const AccelEntry* e = find_accel(default_accel);
    REQUIRE(e != nullptr);
    CHECK(e->name == default_accel);
}

TEST_CASE("a spec names every parameter that takes effect in canonical order, defaults included",
          "[accel][spec]") {
    CHECK(parse_accel_spec("bvh:binned").canonical() ==
          "bvh:binned,max_leaf=8,bins=16,ct=4,ci=1,block=1,threads=0");
    CHECK(parse_accel_spec("bvh:binned,bins=32,max_leaf=4").canonical() ==
          "bvh:binned,max_leaf=4,bins=32,ct=4,ci=1,block=1,threads=0");
    CHECK(parse_accel_spec("kdtree:sah,ct=1,ci=80,empty_bonus=0.5").canonical() ==
          "kdtree:sah,ct=1,ci=80,empty_bonus=0.5,max_depth=0,min_leaf=1,perfect=1,threads=0,"
          "traversal=havran,leaves=soa");
    CHECK(parse_accel_spec("grid:uniform,density=4").canonical() ==
          "grid:uniform,density=4,max_res=512,threads=0");
    CHECK(parse_accel_spec("brute").canonical() == "brute");
    // Reals are stored as floats and printed as the shortest text that reads back the same.
    CHECK(parse_accel_spec("bvh:sweep,ct=0.1").canonical() ==
          "bvh:sweep,max_leaf=8,ct=0.1,ci=1,block=1,threads=0");
    // A layout row names its source builder's keys only: no morton_bits with from=pbinned, no SAH
    // keys with from=lbvh, no leaf_align with leaves=ids.
    CHECK(parse_accel_spec("bvh8").canonical() ==
          "bvh8,from=pbinned,leaves=soa,leaf_align=4,order=area,collapse=sah,bounds=aabb,"
          "max_leaf=8,bins=16,ct=4,ci=1,block=4,threads=0");
    CHECK(parse_accel_spec("bvh8,from=lbvh,leaves=ids").canonical() ==
          "bvh8,from=lbvh,leaves=ids,order=area,collapse=sah,bounds=aabb,max_leaf=8,"
          "morton_bits=10,threads=0");
    CHECK(parse_accel_spec("bvh:pair,from=sweep").canonical() ==
          "bvh:pair,from=sweep,leaves=soa,leaf_align=4,order=area,max_leaf=32,ct=16,ci=1,block=4,"
          "threads=0");
}

TEST_CASE("a parameter depends on a choice declared before it, and threads only on the build",
          "[accel][spec]") {
    for (const AccelEntry& e : accel_registry()) {
        for (std::size_t i = 0; i < e.params.size(); ++i) {
            const ParamSpec& p = e.params[i];
            CAPTURE(e.name, p.key);
            CHECK(p.build_only == (p.key == "threads"));
            if (p.needs.empty()) {
                CHECK(p.needs_values.empty());
                continue;
            }
            // Declared before: no cycles, and the canonical spec names the setting first.
            std::size_t j = 0;
            while (j < i && e.params[j].key != p.needs) {
                ++j;
            }
            REQUIRE(j < i);
            REQUIRE(e.params[j].kind == ParamKind::choice);
            CHECK(!p.needs_values.empty());
            for (std::string_view v : p.needs_values) {
                CAPTURE(v);
                const auto& c = e.params[j].choices;
                CHECK(std::find(c.begin(), c.end(), v) != c.end());
            }
        }
    }
}

TEST_CASE("every row's canonical spec parses back to itself", "[accel][spec]") {
    for (const AccelEntry& e : accel_registry()) {
        const AccelSpec d = default_spec(e);
        CAPTURE(d.canonical());
        const AccelSpec again = parse_accel_spec(d.canonical());
        CHECK(again.entry == &e);
        CHECK(again.values == d.values);
        CHECK(again.canonical() == d.canonical());
        for (const ParamSpec& p : e.params) {
            CAPTURE(p.key);
            CHECK(!p.help.empty());
            CHECK(p.default_value >= p.min);
            CHECK(p.default_value <= p.max);
            CHECK(d.value(p.key) == p.default_value);
        }
    }
}

TEST_CASE("bad specs are one-line errors naming the spec and the key", "[accel][spec]") {
    using Catch::Contains;
    const auto error = [](const std::string& spec) {
        try {
            parse_accel_spec(spec);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string unknown_key = error("bvh:binned,leaf=8");
    CHECK_THAT(unknown_key,
               Contains("bvh:binned,leaf=8") && Contains("'leaf'") && Contains("max_leaf"));
    CHECK_THAT(error("bvh:binned,max_leaf=0"),
               Contains("max_leaf=0") && Contains("outside [1, 1073741823]"));
    CHECK_THAT(error("bvh:binned,max_leaf=2.5"), Contains("whole number"));
    CHECK_THAT(error("bvh:binned,max_leaf=abc"), Contains("needs a number"));
    CHECK_THAT(error("bvh:binned,max_leaf=nan"), Contains("needs a number"));
    CHECK_THAT(error("bvh:binned,max_leaf="), Contains("needs a number"));
    CHECK_THAT(error("bvh:binned,max_leaf=4,max_leaf=8"), Contains("given twice"));
    CHECK_THAT(error("bvh:binned,"), Contains("empty parameter"));
    CHECK_THAT(error("bvh:binned,max_leaf"), Contains("not key=value"));
    CHECK_THAT(error("bvh:nope"),
               Contains("unknown structure") && Contains("bvh:binned") && Contains("brute"));
    CHECK_THAT(error("brute,max_leaf=2"), Contains("no parameters"));
    CHECK_THAT(error("kdtree:sah,empty_bonus=1"), Contains("outside [0, 0.99]"));
    for (const std::string& spec : {unknown_key, error("bvh:binned,max_leaf=0")}) {
        CHECK(spec.find('\n') == std::string::npos);
    }
}

TEST_CASE("parameter kinds parse, check and print their values", "[accel][spec]") {
    const ParamSpec leaf = integer_param("max_leaf", 4, 1, 64, "h");
    CHECK(leaf.parse("s", "8") == 8);
    CHECK(leaf.format(8) == "8");
    CHECK(leaf.range_text() == "[1, 64]");
    CHECK_THROWS_WITH(leaf.parse("s", "65"), Catch::Contains("outside [1, 64]"));
    CHECK_THROWS_WITH(leaf.parse("s", "1e40"), Catch::Contains("outside"));
    const ParamSpec cost = real_param("ci", 1.5, 1e-3, 1e6, "h");
    CHECK(cost.parse("s", "0.1") == static_cast<double>(0.1f));
    CHECK(cost.format(cost.parse("s", "0.1")) == "0.1");
    CHECK(cost.format(1e6) == "1e+06");
    CHECK_THROWS_WITH(cost.parse("s", "inf"), Catch::Contains("needs a number"));
    CHECK_THROWS_WITH(cost.parse("s", "0"), Catch::Contains("outside [0.001, 1e+06]"));
    const ParamSpec from = choice_param("from", 1, {"median", "binned", "sweep"}, "h");
    CHECK(from.default_value == 1);
    CHECK(from.parse("s", "sweep") == 2);
    CHECK(from.format(0) == "median");
    CHECK(from.range_text() == "median|binned|sweep");
    CHECK_THROWS_WITH(from.parse("s", "lbvh"),
                      Catch::Contains("from must be one of median|binned|sweep, not 'lbvh'") &&
                          Catch::Contains("--accel 's'"));
}

TEST_CASE("from= lists exactly the rows that build a binary BVH", "[accel][spec]") {
    const std::vector<std::string> from = test::from_choices();
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 5, 50);
    std::size_t binary_rows = 0;
    for (const AccelEntry& e : accel_registry()) {
        CAPTURE(e.name);
        for (const ParamSpec& p : e.params) {
            if (p.key == "from") {  // every layout row converts the same builders
                CHECK(std::vector<std::string>(p.choices.begin(), p.choices.end()) == from);
            }
        }
        if (std::holds_alternative<Bvh>(build_accel(e.name, soup.input()))) {
            ++binary_rows;
            const std::string name(e.name);
            REQUIRE(name.rfind("bvh:", 0) == 0);
            CHECK(std::find(from.begin(), from.end(), name.substr(4)) != from.end());
        }
    }
    CHECK(binary_rows == from.size());
}

TEST_CASE("max_leaf reaches the builder: other trees, same answers", "[accel][spec]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 21, 2000);
    const std::vector<Rayf> rays = test::random_rays(soup, 21, 300);
    const Bvh one = std::get<Bvh>(build_accel("bvh:binned,max_leaf=1", soup.input()));
    const Bvh eight = std::get<Bvh>(build_accel("bvh:binned,max_leaf=8", soup.input()));
    CHECK(one.config.max_leaf_size == 1);
    CHECK(eight.config.max_leaf_size == 8);
    CHECK(one.info().nodes > eight.info().nodes);
    CHECK(one.info().bytes_per_prim > eight.info().bytes_per_prim);
    test::check_agrees_with_brute_force(one, soup, rays);
    test::check_agrees_with_brute_force(eight, soup, rays);
    const TraversalStats st_one = test::closest_hit_stats(one, soup, rays);
    const TraversalStats st_eight = test::closest_hit_stats(eight, soup, rays);
    CHECK(st_one.nodes > st_eight.nodes);
    CHECK(st_one.prims < st_eight.prims);
}

}  // namespace
}  // namespace rtlab
