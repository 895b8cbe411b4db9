// mesh/: round trips through every format (geometry and triangle order kept), fan order of
// polygons, statistics, cleaning, and rejection of malformed files with a message naming the file.
#include "mesh/mesh_clean.h"
#include "mesh/mesh_io.h"
#include "mesh/mesh_stats.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>

namespace fs = std::filesystem;
using namespace rtlab;
using rtlab::test::TempDir;
using rtlab::test::write_text;

namespace {

std::string read_all(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A closed, consistently oriented (outward) unit cube: 8 vertices, 12 triangles.
TriangleMesh cube() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                   {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    return m;
}

/// A seeded random soup with coordinates that need all 9 significant digits to round-trip.
TriangleMesh random_mesh(std::uint32_t seed, std::size_t vertices, std::size_t triangles) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-1000.0f, 1000.0f);
    TriangleMesh m;
    for (std::size_t i = 0; i < vertices; ++i) {
        m.positions.push_back({coord(rng), coord(rng) * 1e-3f, coord(rng) * 1e-6f});
    }
    std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(vertices - 1));
    while (m.triangles.size() < triangles) {
        const std::array<std::uint32_t, 3> t{pick(rng), pick(rng), pick(rng)};
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
            m.triangles.push_back(t);
        }
    }
    return m;
}

/// Corners of every triangle, in order: what survives formats that re-index (STL).
std::vector<std::array<Vec3f, 3>> corner_list(const TriangleMesh& m) {
    std::vector<std::array<Vec3f, 3>> out;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        out.push_back(m.corners(i));
    }
    return out;
}

/// load_mesh(p) throws an Error whose message names p and contains `needle`.
void require_rejected(const fs::path& p, const std::string& needle) {
    CAPTURE(p.string(), needle);
    try {
        (void)load_mesh(p);
        FAIL("accepted a malformed file");
    } catch (const Error& e) {
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find(p.string()) == 0);
        CHECK(msg.find(needle) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
}

}  // namespace

TEST_CASE("mesh files round-trip geometry and triangle order", "[mesh][io]") {
    TempDir dir("rtlab_mesh_test_");
    const auto seed = GENERATE(1u, 2u, 3u);
    TriangleMesh m = random_mesh(seed, 60, 100);
    m.positions.push_back({0.1f, -0.2f, 1e-30f});  // unreferenced: kept by indexed formats
    CAPTURE(seed);
    struct Case {
        const char* name;
        bool binary;
        bool indexed;  ///< vertices kept as they are (STL welds and re-indexes)
    };
    for (const Case c :
         {Case{"m.obj", false, true}, Case{"a.ply", false, true}, Case{"b.ply", true, true},
          Case{"m.off", false, true}, Case{"a.stl", false, false}, Case{"b.stl", true, false}}) {
        CAPTURE(c.name);
        const fs::path p = dir.path / c.name;
        save_mesh(m, p, {.binary = c.binary});
        const TriangleMesh back = load_mesh(p);
        if (c.indexed) {
            CHECK(back == m);
        } else {
            CHECK(corner_list(back) == corner_list(m));
        }
    }
    CHECK(read_all(dir.path / "a.ply").find("format ascii") != std::string::npos);
    CHECK(read_all(dir.path / "b.ply").find("format binary_little_endian") != std::string::npos);
    CHECK(read_all(dir.path / "a.stl").rfind("solid", 0) == 0);
    CHECK(fs::file_size(dir.path / "b.stl") == 84 + 50 * m.triangle_count());
    // Nothing but the targets is left in the folder (temporaries were renamed).
    CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 6);
}

TEST_CASE("polygons are fanned from their first vertex, in face order", "[mesh][io]") {
    TempDir dir("rtlab_mesh_test_");
    // Face 0: quad, face 1: triangle, face 2: pentagon (vertex numbers 0-based).
    const std::vector<std::array<std::uint32_t, 3>> expected{{0, 1, 2}, {0, 2, 3}, {4, 1, 0},
                                                             {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    const std::string verts = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0\n";
    std::string obj;
    for (const char* v : {"0 0 0", "1 0 0", "1 1 0", "0 1 0", "0.5 2 0"}) {
        obj += std::string("v ") + v + "\n";
    }
    obj += "f 1 2 3 4\nf 5 2 1\nf 1 2 3 4 5\n";
    write_text(dir.path / "p.obj", obj);
    write_text(dir.path / "p.off", "OFF\n5 3 0\n" + verts + "4 0 1 2 3\n3 4 1 0\n5 0 1 2 3 4\n");
    write_text(dir.path / "p.ply",
               "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
               "property float z\nelement face 3\nproperty list uchar int vertex_indices\n"
               "end_header\n" +
                   verts + "4 0 1 2 3\n3 4 1 0\n5 0 1 2 3 4\n");
    for (const char* name : {"p.obj", "p.off", "p.ply"}) {
        CAPTURE(name);
        const TriangleMesh m = load_mesh(dir.path / name);
        CHECK(m.vertex_count() == 5);
        CHECK(m.triangles == expected);
    }
}

TEST_CASE("mesh statistics: closed cube, open cube, non-manifold, orientation", "[mesh][stats]") {
    const TriangleMesh closed = cube();
    const MeshStats s = mesh_stats(closed);
    CHECK(s.closed);
    CHECK(s.vertices == 8);
    CHECK(s.triangles == 12);
    CHECK(s.edges == 18);
    CHECK(s.boundary_edges == 0);
    CHECK(s.non_manifold_edges == 0);
    CHECK(s.degenerate_triangles == 0);
    CHECK(s.bounds == Bounds3f({0, 0, 0}, {1, 1, 1}));

    TriangleMesh open = closed;
    open.triangles.pop_back();  // one hole: a triangle's three edges become boundary edges
    const MeshStats so = mesh_stats(open);
    CHECK_FALSE(so.closed);
    CHECK(so.boundary_edges == 3);
    CHECK(so.non_manifold_edges == 0);

    TriangleMesh flipped = closed;
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    const MeshStats sf = mesh_stats(flipped);
    CHECK_FALSE(sf.closed);
    CHECK(sf.inconsistent_edges == 3);
    CHECK(sf.boundary_edges == 0);

    TriangleMesh fin = closed;  // a fin on edge 0-1 makes it shared by three triangles
    fin.positions.push_back({0.5f, -1, 0.5f});
    fin.triangles.push_back({0, 1, 8});
    const MeshStats sn = mesh_stats(fin);
    CHECK_FALSE(sn.closed);
    CHECK(sn.non_manifold_edges == 1);
    CHECK(sn.boundary_edges == 2);

    TriangleMesh dup = closed;
    dup.triangles.push_back({1, 0, 2});     // same set as {0, 2, 1}
    dup.positions.push_back({2, 2, 2});     // unreferenced
    dup.triangles.push_back({0, 1, 1});     // repeated index
    dup.positions.push_back({0.5f, 0, 0});  // collinear with 0 and 1
    dup.triangles.push_back({0, 1, 9});     // zero area
    const MeshStats sd = mesh_stats(dup);
    CHECK(sd.duplicate_triangles == 1);
    CHECK(sd.degenerate_triangles == 2);
    CHECK(sd.unreferenced_vertices == 1);
    CHECK_FALSE(sd.closed);
}

TEST_CASE("clean_mesh drops non-finite and zero-area triangles and unused vertices",
          "[mesh][clean]") {
    TriangleMesh m = cube();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    m.positions.push_back({nan, 0, 0});   // 8
    m.positions.push_back({0.5f, 0, 0});  // 9: collinear with 0, 1
    m.positions.push_back({7, 7, 7});     // 10: unused from the start
    m.triangles.insert(m.triangles.begin() + 3, {0, 8, 1});
    m.triangles.push_back({0, 9, 1});
    m.triangles.push_back({2, 2, 3});
    const CleanReport r = clean_mesh(m);
    CHECK(r.non_finite_triangles == 1);
    CHECK(r.degenerate_triangles == 2);
    CHECK(r.triangles_removed() == 3);
    CHECK(r.unreferenced_vertices == 3);
    CHECK(m == cube());  // what stays keeps its order and indices
    CHECK(mesh_stats(m).closed);
}

TEST_CASE("save_mesh is atomic and rejects invalid meshes", "[mesh][io]") {
    TempDir dir("rtlab_mesh_test_");
    const fs::path p = dir.path / "c.ply";
    save_mesh(cube(), p);
    const std::string before = read_all(p);
    TriangleMesh bad = cube();
    bad.triangles.push_back({0, 1, 42});
    CHECK_THROWS_WITH(save_mesh(bad, p),
                      Catch::Contains("c.ply") && Catch::Contains("out of range"));
    CHECK(read_all(p) == before);
    CHECK_THROWS_WITH(save_mesh(TriangleMesh{}, dir.path / "e.obj"), Catch::Contains("no faces"));
    CHECK_THROWS_WITH(save_mesh(cube(), dir.path / "nope" / "c.obj"),
                      Catch::Contains("does not exist"));
    CHECK_THROWS_WITH(save_mesh(cube(), dir.path / "c.txt"), Catch::Contains("unknown mesh"));
    TriangleMesh rep = cube();
    rep.triangles.push_back({0, 0, 1});
    CHECK_THROWS_WITH(save_mesh(rep, dir.path / "r.obj"), Catch::Contains("repeats a vertex"));
    CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
}

TEST_CASE("malformed mesh files are rejected with a one-line message naming the file",
          "[mesh][io][errors]") {
    TempDir dir("rtlab_mesh_test_");
    const fs::path& d = dir.path;
    const std::string ply_head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    struct Text {
        const char* name;
        std::string content;
        const char* needle;
    };
    const std::vector<Text> cases{
        {"empty.obj", "", "empty file"},
        {"garbage.obj", "hello world\nthis is not a mesh\n", "unknown OBJ statement 'hello'"},
        {"binary.obj", std::string("v 0 0 0\n\0\x01\x02", 11), "binary data"},
        {"nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "non-finite"},
        {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n", "non-finite"},
        {"word.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", "is not a number"},
        {"twod.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "3 coordinates"},
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "out of range"},
        {"negrange.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "out of range"},
        {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad face vertex"},
        {"short.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "needs at least 3"},
        {"repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", "repeats vertex"},
        {"nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
        {"noheader.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "no OFF header"},
        {"trunc.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "truncated"},
        {"truncf.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "truncated"},
        {"nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "non-finite"},
        {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "out of range"},
        {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "at least 3"},
        {"counts.off", "OFF\n-3 1 0\n", "bad counts"},
        {"comment.off", "OFF\n# made by hand\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         "comments ('#') in OFF files are not supported"},
        {"notply.ply", "hello\n", "not a PLY file"},
        {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "no end_header"},
        {"huge.ply",
         "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\n"
         "end_header\n",
         "bad element count"},
        {"noz.ply",
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         "end_header\n0 0\n",
         "no scalar property 'z'"},
        {"nan.ply", ply_head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "non-finite"},
        {"trunc.ply", ply_head + "0 0 0\n1 0 0\n", "truncated"},
        {"range.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "out of range"},
        {"short.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "needs at least 3"},
        {"word.ply", ply_head + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "is not a number"},
        {"garbage.stl", "this is not an stl file\n", "not an STL file"},
        {"noend.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
         "no 'endsolid'"},
        {"nan.stl",
         "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\n"
         "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n",
         "non-finite"},
        {"two.stl",
         "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
         "endloop\nendfacet\nendsolid x\n",
         "does not have 3 vertices"},
        {"empty.stl", "solid x\nendsolid x\n", "no faces"},
        {"mesh.txt", "v 0 0 0\n", "unknown mesh extension"},
    };
    for (const Text& c : cases) {
        write_text(d / c.name, c.content);
        require_rejected(d / c.name, c.needle);
    }
    require_rejected(d / "missing.obj", "no such file");
    fs::create_directories(d / "folder.obj");
    require_rejected(d / "folder.obj", "not a regular file");

    // Binary files: truncated at every interesting offset, and with a NaN coordinate patched in.
    save_mesh(cube(), d / "good.ply", {.binary = true});
    save_mesh(cube(), d / "good.stl", {.binary = true});
    const std::string ply = read_all(d / "good.ply");
    const std::string stl = read_all(d / "good.stl");
    const std::size_t body = ply.find("end_header\n") + 11;
    for (const std::size_t keep : {body, body + 5, body + 12 * 8 - 1, ply.size() - 1}) {
        CAPTURE(keep);
        write_text(d / "cut.ply", ply.substr(0, keep));
        require_rejected(d / "cut.ply", "truncated");
    }
    for (const std::size_t keep :
         {std::size_t{0}, std::size_t{50}, std::size_t{84}, stl.size() - 1}) {
        CAPTURE(keep);
        write_text(d / "cut.stl", stl.substr(0, keep));
        require_rejected(d / "cut.stl", keep == 0 ? "empty file" : "not an STL file");
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::string ply_nan = ply;
    std::memcpy(ply_nan.data() + body + 4, &nan, 4);  // vertex 0, y
    write_text(d / "nanbin.ply", ply_nan);
    require_rejected(d / "nanbin.ply", "vertex 0: non-finite y");
    std::string stl_nan = stl;
    std::memcpy(stl_nan.data() + 84 + 50 + 12 + 8, &nan, 4);  // triangle 1, first corner z
    write_text(d / "nanbin.stl", stl_nan);
    require_rejected(d / "nanbin.stl", "triangle 1: non-finite");
    std::string ply_range = ply;
    const std::size_t face0 = body + 8 * 12 + 1;  // after the first face's uchar count
    const std::int32_t big = 1000;
    std::memcpy(ply_range.data() + face0, &big, 4);
    write_text(d / "rangebin.ply", ply_range);
    require_rejected(d / "rangebin.ply", "face 0: vertex index 1000 out of range");
}

TEST_CASE("files with attributes, comments and other layouts load", "[mesh][io]") {
    TempDir dir("rtlab_mesh_test_");
    const std::vector<std::array<std::uint32_t, 3>> expected{{0, 1, 2}, {0, 2, 3}, {3, 2, 1}};
    write_text(dir.path / "attr.obj",
               "# comment\nmtllib missing.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
               "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nusemtl m\ns off\nf 1/1/1 2/2/1 3/3/1\n"
               "g part\nf 1/3/1 3/1/1 4/2/1  # trailing comment\nf 4//1 3//1 -3//1\n");
    write_text(dir.path / "attr.ply",
               "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\n"
               "property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
               "property uchar green\nproperty uchar blue\nelement face 3\n"
               "property list uchar uint vertex_indices\nend_header\n"
               "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n"
               "3 0 1 2\n3 0 2 3\n3 3 2 1\n");
    write_text(dir.path / "attr.off",
               "OFF\n4 3 0\n0 0 0\n1 0 0\n"
               "1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n\n3 3 2 1\n");
    // Attributed OFF (COFF, NOFF) is rejected: OpenMesh's reader misbehaves on it.
    write_text(dir.path / "colour.off",
               "COFF\n4 3 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n"
               "1 1 0 0 0 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n3 0 2 3\n\n3 3 2 1\n");
    CHECK_THROWS_WITH(load_mesh(dir.path / "colour.off"),
                      Catch::Contains("colour.off") && Catch::Contains("only plain OFF"));
    for (const char* name : {"attr.obj", "attr.ply", "attr.off"}) {
        CAPTURE(name);
        const TriangleMesh m = load_mesh(dir.path / name);
        CHECK(m.positions == std::vector<Vec3f>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
        CHECK(m.triangles == expected);
    }
}
