// scene/: parsing a full scene, save/load round trips, errors naming their JSON path, the global
// primitive id contract, and feature detection.
#include "mesh/mesh_io.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace fs = std::filesystem;
using namespace rtlab;
using rtlab::test::TempDir;
using rtlab::test::write_text;

namespace {

/// Two triangles (a unit quad in z = 0) and a third one: 3 primitives.
const char* const tri_obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 4\n";

const char* const full_scene = R"({
  "camera": {"from": [0, 1, 8], "at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40,
             "width": 320, "height": 200},
  "background": [0.1, 0.2, 0.3],
  "lights": [{"type": "point", "position": [5, 5, 5], "color": [1, 0.9, 0.8]},
             {"type": "directional", "direction": [0, 1, 0]}],
  "materials": {
    "glass": {"color": [1, 1, 1], "transmit": 0.9, "ior": 1.5, "fresnel": true,
              "absorption": [0.1, 0, 0], "dispersion": 0.004},
    "floor": {"diffuse": 0.7, "texture": {"type": "checker", "color2": [0, 0, 0], "scale": 0.5}},
    "mirror": {"reflect": 0.8, "specular": 0.5, "shininess": 64}
  },
  "objects": [
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"},
    {"type": "mesh", "file": "tri.obj", "material": "floor"},
    {"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]},
    {"type": "box", "min": [-1, -1, -1], "max": [1, 0, 1], "material": "mirror"},
    {"type": "obb", "center": [3, 0, 0], "axes": [[0, 1, 0], [-1, 0, 0], [0, 0, 1]],
     "half": [1, 2, 3]},
    {"type": "implicit", "surface": "torus", "center": [0, 0, -3], "major": 1.5, "minor": 0.5},
    {"type": "implicit", "surface": "tanglecube", "center": [4, 4, 4], "scale": 0.5}
  ]
})";

}  // namespace

TEST_CASE("a full scene parses with every field", "[scene][io]") {
    TempDir dir("rtlab_scene_test_");
    write_text(dir.path / "tri.obj", tri_obj);
    write_text(dir.path / "s.json", full_scene);
    const Scene s = load_scene(dir.path / "s.json");

    CHECK(s.camera.from == Vec3f{0, 1, 8});
    CHECK(s.camera.fov_deg == 40);
    CHECK(s.camera.width == 320);
    CHECK(s.camera.height == 200);
    CHECK(s.background == Vec3f{0.1f, 0.2f, 0.3f});
    REQUIRE(s.lights.size() == 2);
    CHECK(s.lights[0].kind == LightKind::point);
    CHECK(s.lights[0].color == Vec3f{1, 0.9f, 0.8f});
    CHECK(s.lights[1].kind == LightKind::directional);
    CHECK(s.lights[1].position == Vec3f{0, 1, 0});
    CHECK(s.lights[1].color == Vec3f{1, 1, 1});
    // Materials in file order, then "default" created for the objects without one.
    REQUIRE(s.materials.size() == 4);
    CHECK(s.materials[0].name == "glass");
    CHECK(s.materials[0].transmit == 0.9f);
    CHECK(s.materials[0].fresnel);
    CHECK(s.materials[0].absorption == Vec3f{0.1f, 0, 0});
    CHECK(s.materials[0].dispersion == 0.004f);
    CHECK(s.materials[1].texture.kind == TextureKind::checker);
    CHECK(s.materials[1].texture.scale == 0.5f);
    CHECK(s.materials[1].diffuse == 0.7f);
    CHECK(s.materials[1].ambient == Material{}.ambient);
    CHECK(s.materials[3].name == "default");

    CHECK(s.spheres.size() == 1);
    CHECK(s.spheres[0].radius == 1);
    CHECK(s.spheres[0].material == 0);
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].file == "tri.obj");
    CHECK(s.meshes[0].mesh.triangle_count() == 3);
    CHECK(s.meshes[0].material == 1);
    CHECK(s.polygons[0].vertices.size() == 4);
    CHECK(s.polygons[0].material == 3);
    CHECK(s.boxes[0].bounds == Bounds3f({-1, -1, -1}, {1, 0, 1}));
    CHECK(s.obbs[0].half == Vec3f{1, 2, 3});
    CHECK(s.implicits[0].kind == ImplicitKind::torus);
    CHECK(s.implicits[0].major == 1.5f);
    CHECK(s.implicits[1].kind == ImplicitKind::tanglecube);
    CHECK(s.implicits[1].scale == 0.5f);
    const std::vector<ObjectRef> order{
        {PrimType::sphere, 0}, {PrimType::mesh, 0},     {PrimType::polygon, 0}, {PrimType::box, 0},
        {PrimType::obb, 0},    {PrimType::implicit, 0}, {PrimType::implicit, 1}};
    CHECK(s.order == order);
    // The OBB's box: axis 0 = +y with half 1, axis 1 = -x with half 2, z half 3.
    CHECK(object_bounds(s, s.order[4]) == Bounds3f({1, -1, -3}, {5, 1, 3}));
}

TEST_CASE("the primitive type table agrees with PrimType and Scene", "[scene]") {
    std::size_t n = 0;
    for_each_type<PrimTypes>([&]<class P>() {
        CAPTURE(P::name);
        CHECK(static_cast<std::size_t>(prim_type_v<P>) == n++);
        CHECK(to_string(prim_type_v<P>) == P::name);
        Scene s;
        const ObjectRef r = s.add(typename P::Object{});
        CHECK(r == ObjectRef{prim_type_v<P>, 0});
        CHECK(P::objects(s).size() == 1);
        CHECK(primitive_id_base(s).back() == P::count(P::objects(s)[0]));
    });
    CHECK(n == prim_type_count);
}

TEST_CASE("scenes round-trip through save_scene and load_scene", "[scene][io]") {
    TempDir dir("rtlab_scene_test_");
    write_text(dir.path / "tri.obj", tri_obj);
    write_text(dir.path / "s.json", full_scene);
    const Scene s = load_scene(dir.path / "s.json");

    SECTION("meshes written beside the scene") {
        fs::create_directories(dir.path / "out");
        save_scene(s, dir.path / "out" / "copy.json", true);
        CHECK(fs::exists(dir.path / "out" / "copy.mesh0.ply"));
        Scene expected = s;
        expected.meshes[0].file = "copy.mesh0.ply";
        CHECK(load_scene(dir.path / "out" / "copy.json") == expected);
    }
    SECTION("meshes referenced by their file") {
        save_scene(s, dir.path / "same.json", false);
        CHECK(load_scene(dir.path / "same.json") == s);
    }
    SECTION("saving again over its own earlier output, never over a file rtlab did not write") {
        save_scene(Scene{}, dir.path / "again.json", false);
        save_scene(s, dir.path / "again.json", false);
        CHECK(load_scene(dir.path / "again.json") == s);
        CHECK_THROWS_WITH(save_scene(Scene{}, dir.path / "s.json", false),
                          Catch::Contains("s.json: exists and was not written by rtlab"));
        CHECK(load_scene(dir.path / "s.json") == s);
    }
    SECTION("a mesh without a file needs write_meshes") {
        Scene t = s;
        t.meshes[0].file.clear();
        CHECK_THROWS_WITH(save_scene(t, dir.path / "t.json", false), Catch::Contains("no file"));
        CHECK_FALSE(fs::exists(dir.path / "t.json"));
    }
}

TEST_CASE("scene errors name the file and the JSON path", "[scene][io][errors]") {
    TempDir dir("rtlab_scene_test_");
    write_text(dir.path / "tri.obj", tri_obj);
    const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1})";
    const auto objects = [&](const std::string& second) {
        return R"({"objects": [)" + sphere + ", " + second + "]}";
    };
    struct Case {
        std::string json;
        std::string message;  ///< expected text after "x.json: "
    };
    const std::vector<Case> cases{
        {objects(R"({"type": "sphere", "center": [0, 0, 0], "radius": -2})"),
         "objects[1].radius: must be > 0"},
        {objects(R"({"type": "sphere", "center": [0, 0, 0], "radius": 0})"),
         "objects[1].radius: must be > 0"},
        {objects(R"({"type": "sphere", "center": [0, 0], "radius": 1})"),
         "objects[1].center: must be an array of 3 numbers"},
        {objects(R"({"type": "sphere", "center": [0, "a", 0], "radius": 1})"),
         "objects[1].center[1]: must be a number"},
        {objects(R"({"type": "sphere", "center": [0, 1e39, 0], "radius": 1})"),
         "objects[1].center[1]: must be a finite number"},
        {objects(R"({"type": "sphere", "center": [0, 1e999, 0], "radius": 1})"),
         "invalid JSON: number overflow"},
        {objects(R"({"type": "sphere", "center": [0, 0, 0]})"),
         "objects[1]: missing required key 'radius'"},
        {objects(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "radus": 2})"),
         "objects[1].radus: unknown key"},
        {objects(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"})"),
         "objects[1].material: unknown material 'gold'"},
        {objects(R"({"type": "teapot"})"), "objects[1].type: unknown object type 'teapot'"},
        {objects(R"({"center": [0, 0, 0]})"), "objects[1]: missing required key 'type'"},
        {objects(R"({"type": "box", "min": [0, 0, 0], "max": [1, -1, 1]})"),
         "objects[1].max: must be >= min on every axis"},
        {objects(R"({"type": "obb", "center": [0, 0, 0], "axes": [[1, 0, 0], [0, 1, 0],
             [0, 0, 1]], "half": [1, -1, 1]})"),
         "objects[1].half: components must be > 0"},
        {objects(R"({"type": "obb", "center": [0, 0, 0], "axes": [[1, 0, 0], [1, 0, 0],
             [0, 0, 1]], "half": [1, 1, 1]})"),
         "objects[1].axes[1]: must be orthogonal to axes[0]"},
        {objects(R"({"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0]]})"),
         "objects[1].vertices: needs at least 3 vertices"},
        {objects(R"({"type": "implicit", "surface": "torus", "major": 0.2, "minor": 0.5})"),
         "objects[1].major: must be > minor"},
        {objects(R"({"type": "implicit", "surface": "blob"})"),
         "objects[1].surface: unknown implicit surface 'blob'"},
        {objects(R"({"type": "mesh", "file": "missing.obj"})"), "objects[1].file: "},
        {objects(R"({"type": "mesh", "file": "tri.obj", "material": 3})"),
         "objects[1].material: must be a string"},
        {R"({"objects": [], "camera": {"from": [0, 0, 1], "at": [0, 0, 0], "width": 20000}})",
         "camera.width: must be in 1..16384"},
        {R"({"objects": [], "camera": {"from": [0, 0, 1], "at": [0, 0, 0], "width": 2.5}})",
         "camera.width: must be an integer"},
        {R"({"objects": [], "camera": {"from": [0, 0, 1], "at": [0, 0, 0], "fov_deg": 0}})",
         "camera.fov_deg: must be in (0, 180)"},
        {R"({"objects": [], "camera": {"from": [0, 0, 1], "at": [0, 0, 1]}})",
         "camera.at: must differ from 'from'"},
        {R"({"objects": [], "camera": {"at": [0, 0, 0]}})", "camera: missing required key 'from'"},
        {R"({"objects": [], "lights": [{"type": "spot", "position": [0, 0, 0]}]})",
         "lights[0].type: unknown light type 'spot'"},
        {R"({"objects": [], "lights": [{"type": "point", "position": [0, 0, 0],
             "color": [1, -1, 1]}]})",
         "lights[0].color: components must be >= 0"},
        {R"({"objects": [], "materials": {"m": {"ior": -1}}})", "materials.m.ior: must be > 0"},
        {R"({"objects": [], "materials": {"m": {"shine": 1}}})", "materials.m.shine: unknown key"},
        {R"({"objects": [], "materials": {"m": {"texture": {"type": "wood"}}}})",
         "materials.m.texture.type: unknown texture type 'wood'"},
        {R"({"objects": [], "materials": {"m": {"fresnel": 1}}})",
         "materials.m.fresnel: must be true or false"},
        {R"({"objects": [], "background": [0, 0, -1]})", "background: components must be >= 0"},
        {R"({"objects": {}})", "objects: must be an array"},
        {R"({"lights": []})", "(top level): missing required key 'objects'"},
        {R"({"objects": [], "extra": 1})", "extra: unknown key"},
        {R"([1, 2, 3])", "(top level): must be an object"},
        {R"({"objects": [})", "invalid JSON: "},
    };
    for (const Case& c : cases) {
        CAPTURE(c.json);
        const fs::path p = dir.path / "x.json";
        write_text(p, c.json);
        try {
            (void)load_scene(p);
            FAIL("accepted a bad scene");
        } catch (const Error& e) {
            const std::string msg = e.what();
            CHECK(msg.rfind(p.string() + ": " + c.message, 0) == 0);
            CHECK(msg.find('\n') == std::string::npos);
        }
    }
    CHECK_THROWS_WITH(load_scene(dir.path / "none.json"), Catch::Contains("no such file"));
    CHECK_THROWS_WITH(load_scene(dir.path / "scene.yaml"),
                      Catch::Contains("unknown scene extension"));
}

TEST_CASE("global primitive ids follow file order, meshes in triangle order", "[scene]") {
    TriangleMesh two;
    two.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    two.triangles = {{0, 1, 2}, {1, 3, 2}};
    TriangleMesh three = two;
    three.positions.push_back({5, 5, 5});
    three.triangles.push_back({0, 1, 4});
    Scene s;
    s.materials.push_back(Material{});
    s.add(SphereObject{{0, 0, 0}, 1, 0});
    s.add(MeshObject{two, "two.ply", 0});
    s.add(BoxObject{Bounds3f({0, 0, 0}, {1, 1, 1}), 0});
    s.add(MeshObject{three, "three.ply", 0});
    s.add(ImplicitObject{});
    const std::vector<std::uint32_t> bases = primitive_id_base(s);
    CHECK(bases == std::vector<std::uint32_t>{0, 1, 3, 4, 7, 8});

    const std::vector<Bounds3f> boxes = primitive_bounds(s);
    REQUIRE(boxes.size() == 8);
    for (std::uint32_t id = 0; id < 8; ++id) {
        CAPTURE(id);
        const PrimitiveLocation at = locate_primitive(bases, id);
        REQUIRE(at.object < s.order.size());
        CHECK(bases[at.object] + at.local == id);
        const ObjectRef r = s.order[at.object];
        const Bounds3f expected = r.type == PrimType::mesh
                                      ? s.meshes[r.index].mesh.triangle_bounds(at.local)
                                      : object_bounds(s, r);
        CHECK(boxes[id] == expected);
    }
    CHECK(locate_primitive(bases, 6).object == 3);
    CHECK(locate_primitive(bases, 6).local == 2);
    CHECK(boxes[6] == Bounds3f({0, 0, 0}, {5, 5, 5}));
    CHECK(scene_bounds(s).contains(Bounds3f({-1, -1, -1}, {5, 5, 5})));
}

TEST_CASE("features come from lights and the materials objects use", "[scene][features]") {
    Scene s;
    Material plain;
    Material mirror;
    mirror.name = "mirror";
    mirror.reflect = 0.5f;
    Material glass;
    glass.name = "glass";
    glass.transmit = 1;
    glass.absorption = {0.2f, 0, 0};
    glass.dispersion = 0.01f;
    glass.fresnel = true;
    Material checker;
    checker.name = "checker";
    checker.texture.kind = TextureKind::checker;
    s.materials = {plain, mirror, glass, checker};
    s.add(SphereObject{{0, 0, 0}, 1, 0});
    CHECK(feature_names(features(s)) == std::vector<std::string>{"sphere"});

    s.lights.push_back(Light{});
    s.add(BoxObject{Bounds3f({0, 0, 0}, {1, 1, 1}), 1});
    CHECK(feature_names(features(s)) ==
          std::vector<std::string>{"sphere", "box", "shadows", "reflection"});

    s.add(SphereObject{{3, 0, 0}, 1, 2});
    s.add(ImplicitObject{ImplicitKind::tanglecube, {0, 0, 0}, 1, 0.25f, 1, 3});
    const SceneFeatures f = features(s);
    CHECK(f.refraction);
    CHECK(f.fresnel);
    CHECK(f.absorption);
    CHECK(f.dispersion);
    CHECK(f.textures);
    CHECK(f.prims[static_cast<std::size_t>(PrimType::implicit)]);
    CHECK_FALSE(f.prims[static_cast<std::size_t>(PrimType::mesh)]);

    // Absorption and dispersion need a refractive material; unused materials count for nothing.
    Scene t;
    Material opaque = glass;
    opaque.transmit = 0;
    opaque.fresnel = false;
    t.materials = {opaque, glass};
    t.add(SphereObject{{0, 0, 0}, 1, 0});
    CHECK(feature_names(features(t)) == std::vector<std::string>{"sphere"});
}

TEST_CASE("a bare mesh file loads as a framed one-mesh scene", "[scene][io]") {
    TempDir dir("rtlab_scene_test_");
    write_text(dir.path / "tri.obj", tri_obj);
    const Scene s = load_scene(dir.path / "tri.obj");
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].mesh.triangle_count() == 3);
    CHECK(s.materials.size() == 1);
    CHECK(s.lights.size() == 1);
    CHECK(s.camera.at == Vec3f{0.5f, 0.5f, 0});
    // The bounding sphere (radius sqrt(2)/2) fits in the vertical field of view.
    const float distance = length(s.camera.from - s.camera.at);
    const float half_fov = 0.5f * s.camera.fov_deg * 3.14159265f / 180.0f;
    CHECK(distance * std::sin(half_fov) >= 0.70710f);
    validate_scene(s, "bare");
}
