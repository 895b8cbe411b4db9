// Sweep files: parameter lists expand through the registry's specs, case ids are stable and
// unique, shards hold every case exactly once and keep scenes together where possible.
#include "accel/spec.h"
#include "base/error.h"
#include "sweep/plan.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>

using namespace rtlab;

namespace {

sweep::SweepFile load_text(const std::string& text) {
    const auto file = std::filesystem::temp_directory_path() / "rtlab_sweep_plan_test.json";
    {
        std::ofstream out(file);
        out << text;
    }
    sweep::SweepFile s = sweep::load_sweep_file(file);
    std::filesystem::remove(file);
    return s;
}

const char* three_scenes = R"({
    // comments are allowed
    "scenes": [{"generator": "flake", "size": 1}, {"generator": "flake", "size": 2},
               {"generator": "flake", "size": 1, "as": "mesh", "tess": "uv:8x4"}],
    "structures": [{"spec": "bvh:binned", "max_leaf": [1, 2, 8], "bins": [4, 32]}, "kdtree:sah"],
    "rays": {"kinds": ["primary", "shadow"], "count": 10}
})";

}  // namespace

TEST_CASE("sweep parameter lists multiply out into canonical specs", "[sweep]") {
    const sweep::SweepFile s = load_text(three_scenes);
    REQUIRE(s.specs.size() == 3 * 2 + 1);
    CHECK(s.specs[0] == "bvh:binned,max_leaf=1,bins=4,ct=1,ci=1");
    CHECK(s.specs[1] == "bvh:binned,max_leaf=1,bins=32,ct=1,ci=1");
    CHECK(s.specs[5] == "bvh:binned,max_leaf=8,bins=32,ct=1,ci=1");
    CHECK(s.specs[6] == parse_accel_spec("kdtree:sah").canonical());
}

TEST_CASE("sweep case ids are stable, unique and independent of shards", "[sweep]") {
    const sweep::SweepFile s = load_text(three_scenes);
    const std::vector<sweep::Case> a = sweep::expand_cases(s);
    const std::vector<sweep::Case> b = sweep::expand_cases(load_text(three_scenes));
    REQUIRE(a.size() == 3 * 7 * 2);
    std::set<std::string> ids;
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].id == b[i].id);
        CHECK(a[i].index == i);
        ids.insert(a[i].id);
    }
    CHECK(ids.size() == a.size());
    // A different ray count measures something else: every id changes.
    std::string other = three_scenes;
    other.replace(other.find("\"count\": 10"), 11, "\"count\": 11");
    const std::vector<sweep::Case> c = sweep::expand_cases(load_text(other));
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(ids.count(c[i].id) == 0);
    }
}

TEST_CASE("sweep shards hold every case once and keep scenes together", "[sweep]") {
    const sweep::SweepFile s = load_text(three_scenes);
    const std::vector<sweep::Case> cases = sweep::expand_cases(s);
    for (const std::size_t n : {0, 1, 2, 3, 4, 7, 20, 1000}) {
        const auto shards = sweep::deal_shards(s, cases, n);
        CHECK(shards.size() == (n == 0 ? 3 : std::min<std::size_t>(n, cases.size())));
        std::vector<int> seen(cases.size(), 0);
        for (const auto& shard : shards) {
            CHECK_FALSE(shard.empty());
            std::set<std::size_t> scenes;
            for (const std::size_t i : shard) {
                ++seen[i];
                scenes.insert(cases[i].scene);
            }
            // With at least as many shards as scenes, a shard never mixes scenes.
            if (shards.size() >= s.scenes.size()) {
                CHECK(scenes.size() == 1);
            }
        }
        for (const int k : seen) {
            CHECK(k == 1);
        }
    }
}

TEST_CASE("sweep files are validated before anything runs", "[sweep]") {
    const auto bad = [](const std::string& from, const std::string& to) {
        std::string text = three_scenes;
        text.replace(text.find(from), from.size(), to);
        return text;
    };
    CHECK_THROWS_AS(load_text(bad("\"flake\", \"size\": 2", "\"frobnicate\"")), Error);
    CHECK_THROWS_AS(load_text(bad("\"bins\"", "\"binz\"")), Error);
    CHECK_THROWS_AS(load_text(bad("[1, 2, 8]", "[1, 0]")), Error);
    CHECK_THROWS_AS(load_text(bad("\"shadow\"", "\"umbra\"")), Error);
    CHECK_THROWS_AS(load_text(bad("\"rays\"", "\"methods\": [\"nope\"], \"rays\"")), Error);
    CHECK_THROWS_AS(load_text(bad("\"scenes\"", "\"scenez\"")), Error);
    CHECK_THROWS_WITH(load_text(bad("\"bins\"", "\"binz\"")),
                      Catch::Contains("structures[0]") && Catch::Contains("binz"));
}
