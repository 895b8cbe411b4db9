// The method checks trace, render and sweep share (trace/method_check.h): scene_families() finds
// without building what a SceneTracer builds sets for, and method_use() applies one rule.
#include "trace/method_check.h"

#include "base/error.h"
#include "datasets_gen/generators.h"
#include "datasets_gen/tessellate.h"
#include "scene/scene_io.h"
#include "trace/scene_tracer.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

using namespace rtlab;

namespace {

Scene generated(const std::string& name, int size, bool as_mesh) {
    gen::GenOptions o;
    o.size = size;
    o.as_mesh = as_mesh;
    o.tess = gen::parse_sphere_tess("uv:8x4");
    return gen::generate(name, o);
}

}  // namespace

TEST_CASE("scene_families names the families a tracer builds sets for", "[method_check]") {
    const std::filesystem::path scenes =
        std::filesystem::path(RTLAB_TEST_DATA_DIR).parent_path().parent_path() / "scenes";
    std::vector<Scene> all{generated("flake", 1, false),
                           generated("flake", 1, true),
                           generated("terrain", 1, false),
                           generated("gearbox", 0, false),
                           load_scene(scenes / "cones.json"),
                           load_scene(scenes / "implicit.json"),
                           Scene{}};
    for (const Scene& s : all) {
        TraceSetup setup;
        setup.accel = parse_accel_spec("brute");
        const SceneTracer tracer(s, setup);
        CHECK(scene_families(s) == tracer_families(tracer));
    }
    using Names = std::vector<std::string_view>;
    CHECK(scene_families(all[0]) == Names{"sphere", "polygon"});
    CHECK(scene_families(all[1]) == Names{"triangle"});
    CHECK(scene_families(all[2]) == Names{"triangle", "sphere"});
    CHECK(scene_families(all.back()).empty());
}

TEST_CASE("method_use finds the methods no set would use", "[method_check]") {
    const std::vector<std::string_view> tri{"triangle"};
    const MethodUse some = method_use(tri, {"watertight", "geometric", "geometric"});
    CHECK(some.unused == std::vector<std::string>{"geometric"});
    CHECK(some.unused_families == std::vector<std::string_view>{"sphere"});
    CHECK_FALSE(some.none_used);
    const MethodUse none = method_use(tri, {"geometric", "winding_number"});
    CHECK(none.unused == std::vector<std::string>{"geometric", "winding_number"});
    CHECK(none.unused_families == std::vector<std::string_view>{"sphere", "polygon"});
    CHECK(none.none_used);
    CHECK(method_use(tri, {"watertight"}).unused.empty());
    CHECK_FALSE(method_use(tri, {}).none_used);  // no list: every family's default
    CHECK(method_family("crossing_count") == "polygon");
    CHECK(method_family("nope").empty());
    CHECK_NOTHROW(check_one_method_per_family({"watertight", "geometric", "watertight"}, "x"));
    CHECK_THROWS_WITH(check_one_method_per_family({"watertight", "badouel"}, "--method"),
                      "--method names two methods of the triangle family ('watertight' and "
                      "'badouel'); give at most one per family");
}
