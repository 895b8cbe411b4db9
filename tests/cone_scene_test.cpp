// Cone objects in scenes (scene/prim_cone.h): JSON reading with defaults and the `radius`
// shorthand, round trips, errors naming the JSON path, bounds, normals, and the tessellation
// (gen::append_cone, scene_to_mesh): counts, closedness when capped, outward winding, vertices on
// the surface.
#include "datasets_gen/generators.h"
#include "datasets_gen/tessellate.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace rtlab;
using rtlab::test::TempDir;
using rtlab::test::write_text;

namespace {

const char* const cone_scene = R"({
  "objects": [
    {"type": "cone", "base": [0, 0, 0], "base_radius": 1, "apex": [0, 2, 0], "apex_radius": 0},
    {"type": "cone", "base": [3, 0, 0], "apex": [3, 0, 2], "radius": 0.5, "caps": "both"},
    {"type": "cone", "base": [-3, 0, 0], "base_radius": 0.2, "apex": [-4, 1, 0],
     "apex_radius": 0.6, "caps": "apex"}
  ]
})";

/// The error message of parsing `json`, or "" when it parses.
std::string parse_error(const std::string& json) {
    try {
        static_cast<void>(parse_scene(json, ".", "x.json"));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("cone objects: reading, defaults, round trip", "[scene][cone]") {
    const Scene s = parse_scene(cone_scene, ".", "cones.json");
    REQUIRE(s.cones.size() == 3);
    CHECK(s.cones[0].apex_radius == 0);
    CHECK(s.cones[0].caps == ConeCaps::none);
    CHECK(s.cones[1].base_radius == 0.5f);
    CHECK(s.cones[1].apex_radius == 0.5f);
    CHECK(s.cones[1].caps == ConeCaps::both);
    CHECK(s.cones[2].caps == ConeCaps::apex);
    CHECK(s.order[1] == ObjectRef{PrimType::cone, 1});
    // Axis-aligned cylinder: the box is exactly the two end disks (plus rounding pads).
    const Bounds3f b = object_bounds(s, s.order[1]);
    CHECK(b.lo.x == Approx(2.5f));
    CHECK(b.hi.y == Approx(0.5f));
    CHECK(b.lo.z == Approx(0.0f).margin(1e-5));
    CHECK(b.hi.z == Approx(2.0f));
    TempDir dir("rtlab_cone_scene_");
    save_scene(s, dir.path / "c.json", false);
    CHECK(load_scene(dir.path / "c.json") == s);
}

TEST_CASE("cone objects: errors name the JSON path", "[scene][cone][errors]") {
    const auto one = [](const std::string& cone) { return R"({"objects": [)" + cone + "]}"; };
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 0],
        "radius": 1})")) ==
          "x.json: objects[0].apex: must differ from base (and the axis length "
          "be finite)");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "base_radius": -1, "apex_radius": 1})")) ==
          "x.json: objects[0].base_radius: must be finite and >= 0");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "base_radius": 0, "apex_radius": 0})")) ==
          "x.json: objects[0].base_radius: base_radius and apex_radius must not both be 0");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "radius": 1, "apex_radius": 1})")) ==
          "x.json: objects[0].radius: give either radius or base_radius and apex_radius");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "radius": 1, "caps": "top"})")) ==
          "x.json: objects[0].caps: unknown caps 'top' (none, base, apex, both)");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "base_radius": 1})")) == "x.json: objects[0]: missing required key 'apex_radius'");
    CHECK(parse_error(one(R"({"type": "cone", "apex": [0, 0, 1], "radius": 1})")) ==
          "x.json: objects[0]: missing required key 'base'");
    CHECK(parse_error(one(R"({"type": "cone", "base": [0, 0, 0], "apex": [0, 0, 1],
        "radius": 1, "height": 2})")) == "x.json: objects[0].height: unknown key");
}

TEST_CASE("cone objects: normals outward on the side and the caps", "[scene][cone]") {
    const Scene s = parse_scene(cone_scene, ".", "cones.json");
    // Pointed cone along +y, radius 1 at y = 0, apex at y = 2 (slope -1/2): at (0.5, 1, 0) the
    // normal is (1, 0.5, 0) / |.|.
    const Vec3f n = normalize(ConePrim::normal(s.cones[0], 0, {0.5f, 1, 0}));
    CHECK(n.x == Approx(2 / std::sqrt(5.0f)));
    CHECK(n.y == Approx(1 / std::sqrt(5.0f)));
    // Capped cylinder along +z: the caps face -z and +z, the side faces outwards.
    CHECK(normalize(ConePrim::normal(s.cones[1], 0, {3.1f, 0.2f, 0})) == Vec3f{0, 0, -1});
    CHECK(normalize(ConePrim::normal(s.cones[1], 0, {3.1f, 0.2f, 2})) == Vec3f{0, 0, 1});
    const Vec3f side = normalize(ConePrim::normal(s.cones[1], 0, {3, -0.5f, 1}));
    CHECK(side.y == Approx(-1));
}

TEST_CASE("cone tessellation: counts, closedness, outward winding", "[datasets][cone]") {
    const Scene s = parse_scene(cone_scene, ".", "cones.json");
    const int n = 12;
    for (const ConeObject& c : s.cones) {
        CAPTURE(static_cast<int>(c.caps), c.base_radius, c.apex_radius);
        TriangleMesh m;
        gen::append_cone(m, Vec3d(c.base), static_cast<double>(c.base_radius), Vec3d(c.apex),
                         static_cast<double>(c.apex_radius), has_cap(c.caps, ConeCaps::base),
                         has_cap(c.caps, ConeCaps::apex), n);
        const bool pointed = c.base_radius == 0 || c.apex_radius == 0;
        std::size_t want = pointed ? n : 2 * n;
        want += has_cap(c.caps, ConeCaps::base) && c.base_radius > 0 ? n : 0;
        want += has_cap(c.caps, ConeCaps::apex) && c.apex_radius > 0 ? n : 0;
        CHECK(m.triangle_count() == want);
        const bool closed = (c.base_radius == 0 || has_cap(c.caps, ConeCaps::base)) &&
                            (c.apex_radius == 0 || has_cap(c.caps, ConeCaps::apex));
        CHECK(gen::is_closed_manifold(m) == closed);
        // Every triangle faces away from the cone's axis midpoint (the shapes are convex).
        const Vec3f mid = (c.base + c.apex) * 0.5f;
        for (std::size_t i = 0; i < m.triangle_count(); ++i) {
            const auto [p, q, r] = m.corners(i);
            const Vec3f centroid = (p + q + r) / 3.0f;
            CHECK(dot(cross(q - p, r - p), centroid - mid) > 0);
        }
    }
    // A pointed cone alone (closed by its base cap) through scene_to_mesh, with uv:8x4: 16.
    Scene one;
    one.materials.push_back(Material{});
    ConeObject c = s.cones[0];
    c.caps = ConeCaps::base;
    one.add(c);
    gen::SphereTess tess;
    tess.u = 8;
    const TriangleMesh m = gen::scene_to_mesh(one, tess);
    CHECK(m.triangle_count() == 16);
    CHECK(gen::is_closed_manifold(m));
}
