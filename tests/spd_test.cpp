// The SPD databases against the SPD programs' own NFF (tests/data/spd, SF 1 and 2), and NFF
// reading, writing and round trips.
#include "base/error.h"
#include "datasets_gen/generators.h"
#include "datasets_gen/spd_databases.h"
#include "scene/nff_io.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

using namespace rtlab;

namespace {

const std::filesystem::path spd_data = std::filesystem::path(RTLAB_TEST_DATA_DIR) / "spd";

// Every number of a record, in print order (the record kind is compared separately).
std::vector<double> numbers(const nff::Record& r) {
    std::vector<double> out;
    const auto v3 = [&](const Vec3d& v) { out.insert(out.end(), {v.x, v.y, v.z}); };
    std::visit(
        [&](const auto& x) {
            using R = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<R, nff::View>) {
                v3(x.from);
                v3(x.at);
                v3(x.up);
                out.insert(out.end(), {x.angle, x.hither, double(x.width), double(x.height)});
            } else if constexpr (std::is_same_v<R, nff::Background>) {
                v3(x.color);
            } else if constexpr (std::is_same_v<R, nff::Light>) {
                v3(x.position);
                if (x.has_color) {
                    v3(x.color);
                }
            } else if constexpr (std::is_same_v<R, nff::Fill>) {
                v3(x.color);
                out.insert(out.end(), {x.kd, x.ks, x.shine, x.t, x.ior});
            } else if constexpr (std::is_same_v<R, nff::Sphere>) {
                v3(x.center);
                out.push_back(x.radius);
            } else if constexpr (std::is_same_v<R, nff::Cone>) {
                v3(x.base);
                out.push_back(x.base_radius);
                v3(x.apex);
                out.push_back(x.apex_radius);
            } else {
                out.push_back(double(x.vertices.size()));
                out.push_back(double(x.normals.size()));
                for (std::size_t i = 0; i < x.vertices.size(); ++i) {
                    v3(x.vertices[i]);
                    if (!x.normals.empty()) {
                        v3(x.normals[i]);
                    }
                }
            }
        },
        r);
    return out;
}

// Equal to NFF's printed precision: %g keeps 6 significant digits, so a printed value is within
// half a unit of the 6th digit (5e-6 relative); 1e-5 allows the reference's own rounding.
// Values that print as tiny residues of zero (e.g. 6.66134e-16) match within 1e-9.
bool same_printed(double ours, double ref) {
    const double d = std::abs(ours - ref);
    return d <= 1e-5 * std::max(std::abs(ours), std::abs(ref)) || d <= 1e-9;
}

// Compares two documents record by record; returns the first difference ("" when equal).
std::string first_difference(const nff::Document& ours, const nff::Document& ref) {
    if (ours.records.size() != ref.records.size()) {
        return "record counts " + std::to_string(ours.records.size()) + " vs " +
               std::to_string(ref.records.size());
    }
    for (std::size_t i = 0; i < ref.records.size(); ++i) {
        if (ours.records[i].index() != ref.records[i].index()) {
            return "record " + std::to_string(i) + ": different kinds";
        }
        const std::vector<double> a = numbers(ours.records[i]);
        const std::vector<double> b = numbers(ref.records[i]);
        if (a.size() != b.size()) {
            return "record " + std::to_string(i) + ": different sizes";
        }
        for (std::size_t k = 0; k < a.size(); ++k) {
            if (!same_printed(a[k], b[k])) {
                return "record " + std::to_string(i) + " number " + std::to_string(k) + ": " +
                       std::to_string(a[k]) + " vs " + std::to_string(b[k]);
            }
        }
    }
    return "";
}

}  // namespace

TEST_CASE("every SPD database equals the SPD program's NFF at SF 1 and 2", "[spd][nff]") {
    for (const gen::spd::Database& db : gen::spd::databases()) {
        for (int sf = 1; sf <= 2; ++sf) {
            CAPTURE(db.name, sf);
            const auto ref_file =
                spd_data / (std::string(db.name) + "-" + std::to_string(sf) + ".nff");
            REQUIRE(std::filesystem::exists(ref_file));
            const nff::Document ref = nff::load(ref_file);
            const nff::Document ours = db.document(sf);
            CHECK(first_difference(ours, ref) == "");
            // The count formulas agree with what is generated.
            const nff::Counts c = nff::count(ours);
            const nff::Counts f = db.counts(sf);
            CHECK(c.spheres == f.spheres);
            CHECK(c.cones == f.cones);
            CHECK(c.polygons == f.polygons);
            CHECK(c.patches == f.patches);
            CHECK(c.lights == f.lights);
            CHECK(c.vertices == f.vertices);
        }
    }
}

TEST_CASE("SPD count formulas hold at larger sizes", "[spd][nff]") {
    for (const gen::spd::Database& db : gen::spd::databases()) {
        for (int sf = 3; sf <= std::min(4, db.max_size); ++sf) {
            CAPTURE(db.name, sf);
            const nff::Counts c = nff::count(db.document(sf));
            const nff::Counts f = db.counts(sf);
            CHECK(c.spheres == f.spheres);
            CHECK(c.cones == f.cones);
            CHECK(c.polygons + c.patches == f.polygons + f.patches);
            CHECK(c.vertices == f.vertices);
        }
    }
}

TEST_CASE("NFF written and read back gives the same records to printed precision", "[nff]") {
    for (const gen::spd::Database& db : gen::spd::databases()) {
        CAPTURE(db.name);
        const nff::Document d = db.document(2);
        const std::string text = nff::write(d);
        const nff::Document back = nff::parse(text, "round-trip");
        CHECK(first_difference(back, d).empty());
        CHECK(nff::write(back) == text);  // printing is a fixed point after one round
    }
}

TEST_CASE("a scene converted to NFF and back keeps its primitives and lights", "[nff]") {
    gen::GenOptions o;
    o.size = 2;
    const Scene s = gen::generate("flake", o);
    const Scene back = nff::to_scene(nff::from_scene(s), "flake");
    REQUIRE(back.spheres.size() == s.spheres.size());
    REQUIRE(back.polygons.size() == s.polygons.size());
    REQUIRE(back.lights.size() == s.lights.size());
    for (std::size_t i = 0; i < s.spheres.size(); ++i) {
        CHECK(length(back.spheres[i].center - s.spheres[i].center) <= 1e-5f);
        CHECK(back.spheres[i].radius == Approx(s.spheres[i].radius).epsilon(1e-5));
    }
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        CHECK(back.lights[i].color.x == Approx(s.lights[i].color.x).epsilon(1e-6));
    }
    CHECK(back.camera.fov_deg == s.camera.fov_deg);
}

TEST_CASE("NFF lights get the SPD's 1/sqrt(n) intensity", "[nff][spd]") {
    const Scene s = nff::to_scene(gen::spd::find_database("balls")->document(1), "balls");
    REQUIRE(s.lights.size() == 3);
    for (const Light& l : s.lights) {
        CHECK(l.color.x == Approx(0.57735).epsilon(1e-5));
    }
    // The flake generator follows the same rule.
    gen::GenOptions o;
    o.size = 1;
    for (const Light& l : gen::generate("flake", o).lights) {
        CHECK(l.color.y == Approx(1 / std::sqrt(3.0)));
    }
}

TEST_CASE("the flake holds the SPD balls' spheres (breadth-first order)", "[spd][flake]") {
    for (int sf = 1; sf <= 3; ++sf) {
        CAPTURE(sf);
        gen::GenOptions o;
        o.size = sf;
        const Scene flake = gen::generate("flake", o);
        const Scene balls = nff::to_scene(gen::spd::find_database("balls")->document(sf), "balls");
        REQUIRE(flake.spheres.size() == balls.spheres.size());
        std::vector<Vec3f> a;
        std::vector<Vec3f> b;
        for (std::size_t i = 0; i < flake.spheres.size(); ++i) {
            a.push_back(flake.spheres[i].center);
            b.push_back(balls.spheres[i].center);
        }
        const auto less = [](const Vec3f& p, const Vec3f& q) {
            return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
        };
        std::sort(a.begin(), a.end(), less);
        std::sort(b.begin(), b.end(), less);
        for (std::size_t i = 0; i < a.size(); ++i) {
            CHECK(length(a[i] - b[i]) <= 1e-6f);
        }
    }
}

TEST_CASE("bad NFF fails with the file and line", "[nff]") {
    const auto fails_with = [](const std::string& text, const std::string& expected) {
        try {
            (void)nff::parse(text, "x.nff");
            FAIL("no error for: " << text);
        } catch (const Error& e) {
            CHECK_THAT(e.what(), Catch::Contains(expected));
        }
    };
    fails_with("b 0 0 0\nq 1 2\n", "x.nff:2: unknown record 'q'");
    fails_with("s 0 0 0 -1\n", "x.nff:1: sphere radius must be > 0");
    fails_with("p 3\n0 0 0\n1 0 0\n", "x.nff:3: unexpected end of file");
    fails_with("s 0 0 zero 1\n", "x.nff:1: expected a number");
    fails_with("s 0 0 0 1e39\n", "x.nff:1: number '1e39' (s radius) is outside the float range");
    fails_with("v\nfrom 0 0 1\nat 0 0 0\nup 0 1 0\nangle 200\nhither 0\nresolution 8 8\n",
               "x.nff:5: angle must be in (0, 180)");
    fails_with("p 2\n0 0 0\n1 0 0\n", "x.nff:1: p vertex count must be an integer");
    CHECK_THROWS_WITH(nff::to_scene(nff::parse("s 0 0 0 1\n", "y.nff"), "y.nff"),
                      Catch::Contains("y.nff: no view"));
}

TEST_CASE("load_scene reads .nff files", "[nff]") {
    const test::TempDir dir("rtlab_spd_test_");
    const auto file = dir.path / "t.nff";
    nff::save(gen::spd::find_database("tetra")->document(2), file);
    const Scene s = load_scene(file);
    CHECK(s.polygons.size() == 16);
    CHECK(s.lights.size() == 1);
    CHECK(s.camera.fov_deg == 45);
}

TEST_CASE("polygon vertex normals are interpolated and survive JSON and NFF", "[nff][polygon]") {
    PolygonObject tri{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    // At a vertex its own normal; at the centroid the mean; geometric without normals.
    CHECK(length(normalize(PolygonPrim::normal(tri, 0, {1, 0, 0})) - Vec3f{0, 1, 0}) < 1e-6f);
    const Vec3f mid = normalize(PolygonPrim::normal(tri, 0, {1.0f / 3, 1.0f / 3, 0}));
    CHECK(length(mid - normalize(Vec3f{1, 1, 1})) < 1e-5f);
    PolygonObject quad{{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, 0, {}};
    CHECK(normalize(PolygonPrim::normal(quad, 0, {1, 1, 0})).z == Approx(1));
    quad.normals = {{0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}};
    // (0.5, 1.5) lies in the fan's second triangle (0, 2, 3): weights 1/4, 1/4, 1/2.
    const Vec3f q = normalize(PolygonPrim::normal(quad, 0, {0.5f, 1.5f, 0}));
    CHECK(length(q - normalize(Vec3f{0.75f, 0, 0.25f})) < 1e-5f);

    const Scene s = nff::to_scene(gen::spd::find_database("teapot")->document(2), "teapot");
    std::size_t with_normals = 0;
    for (const PolygonObject& p : s.polygons) {
        with_normals += p.normals.empty() ? 0 : 1;
    }
    CHECK(with_normals == 240);
    const test::TempDir dir("rtlab_spd_test_");
    save_scene(s, dir.path / "teapot.json", true);
    CHECK(load_scene(dir.path / "teapot.json").polygons == s.polygons);
    const nff::Document back = nff::from_scene(s);
    CHECK(nff::count(back).patches == 240);
}
