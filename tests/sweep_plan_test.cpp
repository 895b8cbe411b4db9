// Sweep files: parameter lists expand through the registry's specs, case ids are stable and
// unique, shards hold every case exactly once and keep scenes together where possible, and a
// case whose methods its scene would not use is refused when planning.
#include "accel/spec.h"
#include "base/error.h"
#include "support/temp_dir.h"
#include "sweep/plan.h"
#include "sweep/sweep_dir.h"

#include <catch2/catch.hpp>

#include <set>
#include <string>

using namespace rtlab;

namespace {

sweep::SweepFile load_text(const std::string& text) {
    // Each call its own folder, removed even when loading throws (the bad-input cases).
    const test::TempDir dir("rtlab_sweep_plan_test_");
    test::write_text(dir.path / "sweep.json", text);
    return sweep::load_sweep_file(dir.path / "sweep.json");
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
    CHECK(s.specs[0] == "bvh:binned,max_leaf=1,bins=4,ct=4,ci=1,block=1,threads=0");
    CHECK(s.specs[1] == "bvh:binned,max_leaf=1,bins=32,ct=4,ci=1,block=1,threads=0");
    CHECK(s.specs[5] == "bvh:binned,max_leaf=8,bins=32,ct=4,ci=1,block=1,threads=0");
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
    // Exact mode runs one test and keeps no per-ray counts: a named method is refused.
    CHECK_THROWS_WITH(
        load_text(bad("\"rays\"", "\"exact\": true, \"methods\": [\"watertight\"], \"rays\"")),
        Catch::Contains("exact"));
}

TEST_CASE("an exact sweep gives its trace cases ids of their own, others keep theirs", "[sweep]") {
    const std::vector<sweep::Case> plain = sweep::expand_cases(load_text(three_scenes));
    std::string text = three_scenes;
    text.replace(text.find("\"rays\""), 6, "\"exact\": true, \"rays\"");
    const sweep::SweepFile exact = load_text(text);
    CHECK(exact.exact);
    const std::vector<sweep::Case> cases = sweep::expand_cases(exact);
    REQUIRE(cases.size() == plain.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        CHECK(cases[i].id != plain[i].id);
    }
}

TEST_CASE("sweep renders and cross-checks expand into their own cases", "[sweep]") {
    std::string text = three_scenes;
    text.replace(text.rfind('}'), 1, R"(,
    "renders": [{"scenes": ["flake,size=2,as=spheres,tess=uv:16x8,seed=1"],
                 "structures": [{"spec": "bvh:sweep", "max_leaf": [2, 4]}], "aov": ["color", "depth"]}],
    "crosscheck": [{"prim": "sphere", "methods": ["geometric", "stable"], "rays": 100}]
})");
    const sweep::SweepFile s = load_text(text);
    const std::vector<sweep::Case> cases = sweep::expand_cases(s);
    REQUIRE(cases.size() == 3 * 7 * 2 + 1 * 2 * 2 + 2 * 2);
    std::set<std::string> ids;
    std::size_t renders = 0;
    std::size_t crosschecks = 0;
    for (const sweep::Case& c : cases) {
        ids.insert(c.id);
        if (c.type == sweep::CaseType::render) {
            ++renders;
            CHECK(c.scene == 1);  // the scene named by its label
            CHECK((c.kind == "color" || c.kind == "depth"));
            CHECK(c.spec.rfind("bvh:sweep,max_leaf=", 0) == 0);
        } else if (c.type == sweep::CaseType::crosscheck) {
            ++crosschecks;
            CHECK(c.scene == s.scenes.size());
            CHECK(sweep::scene_label(s, c) == "-");
            CHECK((c.kind == "float" || c.kind == "double"));
        }
    }
    CHECK(renders == 4);
    CHECK(crosschecks == 4);
    CHECK(ids.size() == cases.size());
    // Default shards: one per scene plus one for the cross-checks; renders join their scene.
    const auto shards = sweep::deal_shards(s, cases, 0);
    REQUIRE(shards.size() == 4);
    for (const auto& shard : shards) {
        std::set<std::size_t> scenes;
        for (const std::size_t i : shard) {
            scenes.insert(cases[i].scene);
        }
        CHECK(scenes.size() == 1);
    }
    // Unknown labels, AOVs, kinds and methods fail at load time.
    const auto bad = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        t.replace(t.find(from), from.size(), to);
        return t;
    };
    CHECK_THROWS_WITH(load_text(bad("seed=1\"]", "seed=9\"]")),
                      Catch::Contains("renders[0].scenes"));
    CHECK_THROWS_WITH(load_text(bad("\"depth\"]", "\"albedo\"]")),
                      Catch::Contains("renders[0].aov"));
    CHECK_THROWS_WITH(load_text(bad("\"sphere\"", "\"torus\"")),
                      Catch::Contains("crosscheck[0].prim"));
    CHECK_THROWS_WITH(load_text(bad("\"stable\"]", "\"stabel\"]")),
                      Catch::Contains("crosscheck[0].methods"));
}

TEST_CASE("sweep plans refuse a case naming a method its scene would not use", "[sweep]") {
    // `rtlab trace --method watertight` refuses a scene without triangles; a sweep case must not
    // quietly run the sphere and polygon defaults instead and be recorded as done.
    const test::TempDir dir("rtlab_sweep_plan_test_");
    const auto plan = [&](const std::string& methods) {
        test::write_text(dir.path / "sweep.json", R"({
            "scenes": [{"name": "flake1-mesh", "generator": "flake", "size": 1, "as": "mesh",
                        "tess": "uv:8x4"},
                       {"name": "flake1-spheres", "generator": "flake", "size": 1}],
            "structures": ["bvh:binned", "kdtree:sah"],
            "methods": )" + methods + R"(,
            "rays": {"kinds": ["primary", "shadow"], "count": 10}
        })");
        return sweep::plan_into(dir.path / "sweep.json", "", 0, false);
    };
    const std::string file = (dir.path / "sweep.json").string();
    CHECK(plan(R"(["default"])").cases.size() == 2 * 2 * 1 * 2);
    // None of the list used: trace's error, as a one-line plan error naming the case's places.
    CHECK_THROWS_WITH(plan(R"(["default", "watertight"])"),
                      file +
                          ": scenes[1] x methods[1]: method 'watertight' matches no primitive "
                          "of scene 'flake1-spheres' (sphere, polygon)");
    // Part of the list unused (trace warns): refused too, or two cases would measure the same
    // sets under different method lists.
    CHECK_THROWS_WITH(plan(R"(["watertight,stable"])"),
                      file +
                          ": scenes[0] x methods[0]: method 'stable' matches no primitive of "
                          "scene 'flake1-mesh' (triangle)");
    CHECK_THROWS_WITH(plan(R"(["geometric,winding_number"])"),
                      file +
                          ": scenes[0] x methods[0]: methods 'geometric', 'winding_number' "
                          "match no primitive of scene 'flake1-mesh' (triangle)");
    // Two methods of one family (the tracer would ignore the second): refused when loading.
    CHECK_THROWS_WITH(
        plan(R"(["watertight,badouel"])"),
        Catch::Contains("methods[0]") && Catch::Contains("two methods of the triangle family"));
}

TEST_CASE("sweep plans refuse exact mode on a scene with other primitives than triangles",
          "[sweep]") {
    const test::TempDir dir("rtlab_sweep_plan_test_");
    const auto plan = [&](const std::string& scenes) {
        test::write_text(dir.path / "sweep.json", R"({
            "scenes": )" + scenes + R"(,
            "structures": ["bvh8"], "exact": true,
            "rays": {"kinds": ["primary"], "count": 10}
        })");
        return sweep::plan_into(dir.path / "sweep.json", "", 0, false);
    };
    const std::string mesh = R"({"name": "m", "generator": "flake", "size": 1, "as": "mesh"})";
    CHECK(plan("[" + mesh + "]").cases.size() == 1);
    CHECK_THROWS_WITH(
        plan("[" + mesh + R"(, {"name": "s", "generator": "flake", "size": 1}])"),
        Catch::Contains("scenes[1]") && Catch::Contains("exact mode") && Catch::Contains("sphere"));
}
