// Procedural scenes: sphere flake geometry against the SPD definition, tessellation counts and
// closedness, generator counts, determinism and the memory guard.
#include "base/error.h"
#include "datasets_gen/generators.h"
#include "datasets_gen/memory_guard.h"
#include "datasets_gen/sphere_flake.h"
#include "datasets_gen/tessellate.h"
#include "mesh/mesh_stats.h"
#include "scene/scene_io.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

using namespace rtlab;
using namespace rtlab::gen;

namespace {

GenCounts counts_of(const Scene& s) {
    GenCounts c;
    c.spheres = s.spheres.size();
    for (const MeshObject& m : s.meshes) {
        c.triangles += m.mesh.triangle_count();
    }
    c.polygons = s.polygons.size();
    c.cones = s.cones.size();
    for (const PolygonObject& p : s.polygons) {
        c.polygon_vertices += p.vertices.size();
    }
    return c;
}

/// Signed volume enclosed by a closed mesh (positive when it winds outward).
double signed_volume(const TriangleMesh& m) {
    double v = 0;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        const auto c = m.corners(i);
        v += dot(Vec3d(c[0]), cross(Vec3d(c[1]), Vec3d(c[2]))) / 6.0;
    }
    return v;
}

}  // namespace

TEST_CASE("sphere flake counts follow (9^(SF+1)-1)/8", "[datasets][flake]") {
    CHECK(flake_sphere_count(4) == 7381);
    CHECK(flake_sphere_count(8) == 48427561);
    for (int sf = 0; sf <= 5; ++sf) {
        CAPTURE(sf);
        CHECK(sphere_flake(sf).size() == flake_sphere_count(sf));
    }
}

TEST_CASE("sphere flake children are tangent and siblings disjoint", "[datasets][flake]") {
    const std::vector<FlakeSphere> f = sphere_flake(4);
    REQUIRE(f[0].radius == 0.5);
    REQUIRE(f[0].center == Vec3d{0, 0, 0});
    for (std::size_t i = 1; i < f.size(); ++i) {
        const FlakeSphere& c = f[i];
        const FlakeSphere& p = f[c.parent];
        const double d = length(c.center - p.center);
        REQUIRE(c.radius == Approx(p.radius / 3).epsilon(1e-12));
        REQUIRE(std::abs(d - (p.radius + c.radius)) <= 1e-5 * (p.radius + c.radius));
        REQUIRE(length(c.axis - (c.center - p.center) / d) < 1e-9);
    }
    // Children of one parent are stored consecutively, 9 at a time.
    for (std::size_t first = 1; first < f.size(); first += 9) {
        for (std::size_t a = first; a < first + 9; ++a) {
            for (std::size_t b = a + 1; b < first + 9; ++b) {
                REQUIRE(f[a].parent == f[b].parent);
                REQUIRE(length(f[a].center - f[b].center) > f[a].radius + f[b].radius);
            }
        }
    }
}

TEST_CASE("first-level flake children sit at the SPD azimuths and elevations",
          "[datasets][flake]") {
    const std::vector<FlakeSphere> f = sphere_flake(1);
    REQUIRE(f.size() == 10);
    const double deg = 180.0 / std::numbers::pi;
    const double upper = std::asin(std::sqrt(2.0 / 3.0)) * deg;
    CHECK(upper == Approx(54.7356).epsilon(1e-5));
    // balls.c's order: each trio is one upper child and two on the equator.
    const double expected_az[9] = {45, 15, 75, 165, 135, 195, 285, 255, 315};
    for (int k = 0; k < 9; ++k) {
        CAPTURE(k);
        const Vec3d d = normalize(f[static_cast<std::size_t>(k) + 1].center);
        double az = std::atan2(d.y, d.x) * deg;
        if (az < 0) {
            az += 360;
        }
        const double el = std::asin(d.z) * deg;
        CHECK(az == Approx(expected_az[k]).margin(1e-9));
        CHECK(el == Approx(k % 3 == 0 ? upper : 0.0).margin(1e-9));
        CHECK(length(f[static_cast<std::size_t>(k) + 1].center) == Approx(0.5 + 0.5 / 3));
    }
}

TEST_CASE("flake rotation takes +Z onto the child axis and keeps lengths and angles",
          "[datasets][flake]") {
    for (const FlakeSphere& s : sphere_flake(3)) {
        const Vec3d d = normalize(s.axis);
        CHECK(length(flake_rotate(s.axis, {0, 0, 1}) - d) < 1e-6);
        for (int k = 0; k < 9; ++k) {
            const Vec3d o = flake_child_offset(k);
            CHECK(length(flake_rotate(s.axis, o)) == Approx(1).epsilon(1e-12));
            // The angle between offset and +Z is kept: the rotation is rigid.
            CHECK(dot(flake_rotate(s.axis, o), flake_rotate(s.axis, {0, 0, 1})) ==
                  Approx(o.z).margin(1e-9));
        }
    }
}

TEST_CASE("tessellated spheres are closed 2-manifolds with the formula's counts",
          "[datasets][tessellate]") {
    const std::string spec = GENERATE(as<std::string>{}, "uv:16x8", "uv:3x2", "uv:5x3", "uv:64x32",
                                      "cube:1", "cube:2", "cube:7");
    CAPTURE(spec);
    const SphereTess t = parse_sphere_tess(spec);
    CHECK(t.to_string() == spec);
    TriangleMesh m;
    append_sphere(m, {1, 2, 3}, 0.5, t);
    CHECK(m.triangle_count() == t.triangles());
    CHECK(m.vertex_count() == t.vertices());
    CHECK(is_closed_manifold(m));
    const MeshStats st = mesh_stats(m);
    CHECK(st.closed);
    CHECK(st.degenerate_triangles == 0);
    CHECK(signed_volume(m) > 0);
    for (const Vec3f& p : m.positions) {
        CHECK(length(Vec3d(p) - Vec3d{1, 2, 3}) == Approx(0.5).epsilon(1e-6));
    }
    CHECK(parse_sphere_tess("uv:16x8").triangles() == 224);
    CHECK(parse_sphere_tess("cube:4").triangles() == 6 * 16 * 2);
}

TEST_CASE("bad tessellation strings are refused", "[datasets][tessellate]") {
    for (const char* bad : {"", "uv", "uv:", "uv:16", "uv:16x", "uv:2x8", "uv:16x1", "uv:x8",
                            "cube:", "cube:0", "cube:-1", "cube:4x", "sphere:3", "uv:16x8 "}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_sphere_tess(bad), Error);
    }
}

TEST_CASE("every generator's counts match what it builds", "[datasets][generators]") {
    for (const Generator& g : generators()) {
        for (const bool as_mesh : {false, true}) {
            GenOptions o;
            o.size = g.min_size + 1;
            o.as_mesh = as_mesh;
            o.tess = parse_sphere_tess("cube:2");
            CAPTURE(g.name, as_mesh, o.size);
            CHECK((!as_mesh || g.counts(o).cones == 0));  // cones are tessellated too
            const Scene s = generate(g, o);
            CHECK(counts_of(s) == g.counts(o));
            for (const MeshObject& m : s.meshes) {
                for (const auto& t : m.mesh.triangles) {
                    for (const std::uint32_t i : t) {
                        REQUIRE(i < m.mesh.vertex_count());
                    }
                }
                for (const Vec3f& p : m.mesh.positions) {
                    REQUIRE(is_finite(p));
                }
            }
            for (const ObjectRef& r : s.order) {
                const std::size_t n =
                    visit_prim_type(r.type, [&]<class P>() { return P::objects(s).size(); });
                REQUIRE(r.index < n);
            }
        }
    }
}

TEST_CASE("flake scene follows the SPD view, lights and materials", "[datasets][flake]") {
    GenOptions o;
    o.size = 2;
    const Scene s = generate("flake", o);
    CHECK(s.spheres.size() == 91);
    CHECK(s.camera.from == Vec3f{2.1f, 1.3f, 1.7f});
    CHECK(s.camera.at == Vec3f{0, 0, 0});
    CHECK(s.camera.up == Vec3f{0, 0, 1});
    CHECK(s.camera.fov_deg == 45);
    REQUIRE(s.lights.size() == 3);
    CHECK(s.lights[2].position == Vec3f{-3, 1, 5});
    CHECK(s.background == Vec3f{0.078f, 0.361f, 0.753f});
    REQUIRE(s.polygons.size() == 1);
    for (const Vec3f& p : s.polygons[0].vertices) {
        CHECK(p.z == -0.5f);
        CHECK(std::abs(p.x) == 12.0f);
        CHECK(std::abs(p.y) == 12.0f);
    }
    const Material& m = s.materials[s.spheres[0].material];
    CHECK(m.color == Vec3f{1.0f, 0.9f, 0.7f});
    CHECK(m.diffuse == 0.5f);
    CHECK(m.reflect == 0.5f);
    CHECK(m.transmit == 0);
    CHECK(s.materials[s.polygons[0].material].diffuse == 0.8f);
}

TEST_CASE("tetra and terrain triangle counts", "[datasets][spd]") {
    for (int sf = 1; sf <= 5; ++sf) {
        GenOptions o;
        o.size = sf;
        const Scene t = generate("tetra", o);
        CHECK(t.polygons.size() == (std::size_t{1} << (2 * sf)));
        const Scene m = generate("terrain", o);
        CHECK(m.meshes[0].mesh.triangle_count() == 2 * (std::size_t{1} << (2 * sf)));
        CHECK(m.spheres.size() == 4);
        CHECK(m.materials[m.spheres[0].material].transmit > 0);
    }
}

TEST_CASE("generators are deterministic for size and seed", "[datasets][determinism]") {
    for (const char* name : {"flake", "terrain", "soup", "soup_clustered", "slivers", "coplanar"}) {
        CAPTURE(name);
        GenOptions o;
        o.size = 2;
        o.seed = 7;
        CHECK(generate(name, o) == generate(name, o));
        GenOptions other = o;
        other.seed = 8;
        if (std::string(name) != "flake") {
            CHECK_FALSE(generate(name, o) == generate(name, other));
        }
    }
}

TEST_CASE("memory guard refuses huge sizes with the estimate in the message",
          "[datasets][memory]") {
    GenOptions o;
    o.size = 12;  // 3.2e11 spheres
    try {
        (void)generate("flake", o);
        FAIL("flake --size 12 was not refused");
    } catch (const Error& e) {
        const std::string what = e.what();
        CHECK(what.find("needs about") != std::string::npos);
        CHECK(what.find("TiB") != std::string::npos);
        const Generator* g = find_generator("flake");
        CHECK(what.find(format_bytes(estimate_bytes(g->counts(o)))) != std::string::npos);
        CHECK(what.find('\n') == std::string::npos);
    }
    o.size = 3;
    o.memory_limit = 1000;  // bytes: even SF 3 is too big
    CHECK_THROWS_AS(generate("flake", o), Error);
    o.size = 13;
    o.memory_limit = 0;
    CHECK_THROWS_WITH(generate("flake", o), Catch::Contains("out of range"));
    CHECK_THROWS_WITH(generate("nope", o), Catch::Contains("unknown generator"));
}

TEST_CASE("intgrid has integer coordinates and is closed", "[datasets][intgrid]") {
    for (int sf = 0; sf <= 3; ++sf) {
        CAPTURE(sf);
        GenOptions o;
        o.size = sf;
        const Scene s = generate("intgrid", o);
        REQUIRE(s.meshes.size() == 1);
        const TriangleMesh& m = s.meshes[0].mesh;
        CHECK(m.triangle_count() == 12u << (2 * sf));
        CHECK(m.vertex_count() == (6u << (2 * sf)) + 2);
        for (const Vec3f& p : m.positions) {
            REQUIRE(p.x == std::round(p.x));
            REQUIRE(p.y == std::round(p.y));
            REQUIRE(p.z == std::round(p.z));
        }
        CHECK(is_closed_manifold(m));
        CHECK(mesh_stats(m).closed);
        CHECK(signed_volume(m) == Approx(std::pow(2.0, 3 * sf)));
    }
}

TEST_CASE("flake as one mesh: closed spheres plus a floor", "[datasets][flake][tessellate]") {
    GenOptions o;
    o.size = 1;
    o.as_mesh = true;
    o.tess = parse_sphere_tess("uv:16x8");
    const Scene s = generate("flake", o);
    const TriangleMesh m = scene_to_mesh(s, o.tess);
    CHECK(m.triangle_count() == 10 * 224 + 2);
    TriangleMesh spheres;
    for (const MeshObject& mo : s.meshes) {
        if (mo.mesh.triangle_count() > 2) {
            spheres = mo.mesh;
        }
    }
    CHECK(is_closed_manifold(spheres));
    // Analytic spheres flattened give the same triangle count as tessellating at generation.
    o.as_mesh = false;
    CHECK(scene_to_mesh(generate("flake", o), o.tess).triangle_count() == 10 * 224 + 4);
}

TEST_CASE("generated scenes survive save_scene and load_scene", "[datasets][io]") {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "rtlab_datasets_test_io";
    std::filesystem::create_directories(dir);
    for (const char* name : {"flake", "gearbox", "terrain", "lattice"}) {
        CAPTURE(name);
        GenOptions o;
        o.size = 1;
        const Scene s = generate(name, o);
        const std::filesystem::path file = dir / (std::string(name) + ".json");
        save_scene(s, file, true);
        const Scene back = load_scene(file);
        CHECK(counts_of(back) == counts_of(s));
        CHECK(back.camera == s.camera);
        CHECK(back.spheres == s.spheres);
        CHECK(back.polygons == s.polygons);
        CHECK(back.materials == s.materials);
        REQUIRE(back.meshes.size() == s.meshes.size());
        for (std::size_t i = 0; i < s.meshes.size(); ++i) {
            CHECK(back.meshes[i].mesh == s.meshes[i].mesh);
        }
    }
    std::filesystem::remove_all(dir);
}
