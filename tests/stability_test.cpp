// The numerical-stability suite (stability/): the framework (registry, report writers) and the
// fast part of the watertight, intgrid, degenerate, grazing and structures cases, each with the
// default 10,000 rays. Each asserts the property that must hold (zero leaks for watertight +
// robust traversal, rejection of invalid rays, agreement of every structure with a box-free
// loop, no false misses of the robust slab test) and only records the other failure counts.
#include "stability/stability.h"

#include "accel/any_accel.h"
#include "base/host.h"
#include "intersect/triangle/moller_trumbore.h"
#include "intersect/triangle/sphere_mesh.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "stability/leak_tally.h"
#include "stability/report.h"
#include "stability/structure_planes.h"
#include "support/temp_dir.h"
#include "trace/binary_io.h"
#include "trace/scene_tracer.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

namespace {

using rtlab::stab::Row;

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool starts_with(const std::string& s, const std::string& head) {
    return s.rfind(head, 0) == 0;
}

/// Prints every row with failures, so a failing REQUIRE comes with the whole picture, and fails
/// on every row the case classifies as a defect of rtlab (the row is the message).
void log_failures(const std::vector<Row>& rows) {
    for (const Row& r : rows) {
        const std::string line = r.case_name + " | " + r.subject + " | " + r.precision + " | " +
                                 std::to_string(r.failures) + " " + r.failure_kind + " | " + r.note;
        if (r.failures > 0) {
            UNSCOPED_INFO(line);
        }
        if (r.defect) {
            FAIL_CHECK("the stability suite classifies this row as a defect: " << line);
        }
    }
}

}  // namespace

TEST_CASE("stability registry: unique names, every case findable", "[stability]") {
    std::set<std::string> names;
    for (const rtlab::stab::Case& c : rtlab::stab::cases()) {
        CAPTURE(c.name);
        CHECK(names.insert(std::string(c.name)).second);
        CHECK(!c.description.empty());
        CHECK(c.run != nullptr);
        CHECK(rtlab::stab::find_case(c.name) == &c);
    }
    for (const char* mine : {"watertight", "intgrid", "degenerate", "grazing", "structures"}) {
        CHECK(rtlab::stab::find_case(mine) != nullptr);
    }
    CHECK(rtlab::stab::find_case("no-such-case") == nullptr);
}

TEST_CASE("stability report: markdown table and JSON with NaN as null", "[stability]") {
    rtlab::stab::ReportHeader h;
    h.command = "rtlab stability --rays 5";
    h.revision = "abc123";
    h.compiler = rtlab::stab::compiler_description();
    h.cpu = rtlab::cpu_model();
    h.options.rays = 5;
    rtlab::stab::CaseResult c;
    c.name = "demo";
    c.description = "A demo case.";
    Row r;
    r.case_name = "demo";
    r.subject = "a|b";
    r.precision = "float";
    r.rays = 5;
    r.failures = 2;
    r.failure_kind = "leaks";
    r.max_rel_t_err = 1.5e-7;
    r.median_rel_t_err = 0;
    r.ns_per_ray = 12.25;
    r.note = "say \"hi\"";
    c.rows.push_back(r);
    const std::vector<rtlab::stab::CaseResult> results{c};

    const std::string md = rtlab::stab::to_markdown(h, results);
    CHECK(md.find("`rtlab stability --rays 5`") != std::string::npos);
    CHECK(md.find("`abc123`") != std::string::npos);
    CHECK(md.find("## demo") != std::string::npos);
    CHECK(md.find("| a\\|b | float | 5 | 2 (leaks) | 1.5e-07 | 0 | 12.2 | say \"hi\" |") !=
          std::string::npos);

    const std::string js = rtlab::stab::to_json(h, results);
    CHECK(js.find("\"subject\":\"a|b\"") != std::string::npos);
    CHECK(js.find("\"note\":\"say \\\"hi\\\"\"") != std::string::npos);
    CHECK(js.find("\"failures\":2") != std::string::npos);
    r.max_rel_t_err = std::numeric_limits<double>::quiet_NaN();
    c.rows = {r};
    const std::vector<rtlab::stab::CaseResult> nan_results{c};
    CHECK(rtlab::stab::to_json(h, nan_results).find("\"max_rel_t_err\":null") != std::string::npos);
    CHECK(rtlab::stab::to_markdown(h, nan_results).find("| - | 0 |") != std::string::npos);

    const rtlab::test::TempDir dir("rtlab_stability_test_");
    const auto file = dir.path / "report.md";
    rtlab::stab::write_report(file, md);
    std::ifstream in(file);
    std::stringstream back;
    back << in.rdbuf();
    CHECK(back.str() == md);
}

TEST_CASE("stability fixture: inside rays are deterministic and start inside", "[stability]") {
    const rtlab::TriangleMesh mesh = rtlab::stab::watertight_sphere(7);
    CHECK(mesh.triangle_count() == 720);
    const auto a = rtlab::stab::inside_rays(mesh, 300, 7);
    const auto b = rtlab::stab::inside_rays(mesh, 300, 7);
    REQUIRE(a.size() == 300);
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].org == b[i].org);
        CHECK(a[i].dir == b[i].dir);
        CHECK(rtlab::length(a[i].org) < 0.51f);
        CHECK(rtlab::is_valid(a[i]));
    }
}

/// Every robust watertight row is leak-free; returns how many there were.
static std::size_t require_watertight_robust_tight(const std::vector<Row>& rows) {
    std::size_t checked = 0;
    for (const Row& r : rows) {
        CAPTURE(r.case_name, r.subject, r.failures);
        CHECK(r.rays == 10000);
        if (starts_with(r.subject, "watertight + ") && ends_with(r.subject, " robust")) {
            CHECK(r.failures == 0);
            ++checked;
        }
    }
    return checked;
}

/// Every exact-mode row is leak-free and agrees with exact brute force (no defect); returns how
/// many there were.
static std::size_t require_exact_tight(const std::vector<Row>& rows) {
    std::size_t checked = 0;
    for (const Row& r : rows) {
        if (starts_with(r.subject, "exact + ")) {
            CAPTURE(r.case_name, r.subject, r.failures, r.note);
            CHECK(r.failures == 0);
            CHECK_FALSE(r.defect);
            ++checked;
        }
    }
    return checked;
}

static rtlab::stab::Selection watertight_robust_only() {
    rtlab::stab::Selection sel;
    sel.methods = {"watertight"};
    sel.plain = false;
    return sel;
}

TEST_CASE("stability watertight: watertight + robust never leaks on any structure", "[stability]") {
    const std::vector<Row> rows = rtlab::stab::run_watertight({}, watertight_robust_only());
    log_failures(rows);
    REQUIRE(rows.size() == rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
}

TEST_CASE("stability watertight, every method, structure and traversal", "[.stability-full]") {
    const std::vector<Row> rows = rtlab::stab::run_watertight({});
    log_failures(rows);
    REQUIRE(rows.size() == (4 * 2 + 1) * rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
    CHECK(require_exact_tight(rows) == rtlab::stab::leak_case_specs().size());
}

TEST_CASE("stability: exact mode never leaks and equals exact brute force on every structure",
          "[stability]") {
    rtlab::stab::Options opt;
    opt.rays = 600;
    rtlab::stab::Selection sel;
    sel.methods = {"exact"};
    using Run = std::vector<Row> (*)(const rtlab::stab::Options&, const rtlab::stab::Selection&);
    for (const Run run : {Run{&rtlab::stab::run_watertight}, Run{&rtlab::stab::run_adversarial},
                          Run{&rtlab::stab::run_intgrid}}) {
        const std::vector<Row> rows = run(opt, sel);
        log_failures(rows);
        REQUIRE(rows.size() == rtlab::stab::leak_case_specs().size());
        CHECK(require_exact_tight(rows) == rows.size());
    }
}

TEST_CASE("stability adversarial: rays at each structure's own planes never leak robust",
          "[stability]") {
    const std::vector<Row> rows = rtlab::stab::run_adversarial({}, watertight_robust_only());
    log_failures(rows);
    REQUIRE(rows.size() == rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
}

TEST_CASE("stability adversarial, every method, structure and traversal", "[.stability-full]") {
    const std::vector<Row> rows = rtlab::stab::run_adversarial({});
    log_failures(rows);
    REQUIRE(rows.size() == (4 * 2 + 1) * rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
    CHECK(require_exact_tight(rows) == rtlab::stab::leak_case_specs().size());
}

TEST_CASE("stability adversarial: rays are deterministic, start in the kernel and aim at planes",
          "[stability]") {
    const std::vector<rtlab::Scene> scenes = rtlab::stab::adversarial_scenes(3);
    REQUIRE(scenes.size() >= 5);
    for (const char* spec : {"kdtree:sah", "grid:uniform", "bvh8"}) {
        CAPTURE(spec);
        const rtlab::TriangleMesh& mesh = scenes[2].meshes[0].mesh;
        std::vector<rtlab::Bounds3f> boxes;
        for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
            boxes.push_back(mesh.triangle_bounds(i));
        }
        const rtlab::AnyAccel accel = rtlab::build_accel(spec, rtlab::BuildInput{boxes, {}});
        const auto a = rtlab::stab::adversarial_rays(mesh, accel, 600, 3);
        const auto b = rtlab::stab::adversarial_rays(mesh, accel, 600, 3);
        REQUIRE(a.size() == 600);
        std::size_t on_plane = 0;
        const auto planes = rtlab::stab::structure_planes(accel);
        REQUIRE(!planes.empty());
        for (std::size_t i = 0; i < a.size(); ++i) {
            CHECK(a[i].org == b[i].org);
            CHECK(a[i].dir == b[i].dir);
            CHECK(rtlab::is_valid(a[i]));
            // From the kernel (inside the unit-ish sphere) or from at least 10 radii away.
            const float r = rtlab::length(a[i].org);
            CHECK((r < 1.0f || r >= 9.0f));
            // Rays starting on a plane of the structure (the grazing kind).
            for (const auto& p : planes) {
                const float o = a[i].org[p.axis];
                if (a[i].org != rtlab::Vec3f{} &&
                    (o == p.pos || o == std::nextafter(p.pos, -INFINITY) ||
                     o == std::nextafter(p.pos, INFINITY))) {
                    ++on_plane;
                    break;
                }
            }
        }
        CHECK(on_plane >= 50);
    }
}

/// A tracer setup: one triangle method under robust traversal of the structure spec.
static rtlab::TraceSetup robust_setup(const char* spec, const char* method) {
    rtlab::TraceSetup setup;
    setup.accel = rtlab::parse_accel_spec(spec);
    setup.methods = {method};
    setup.robust = true;
    return setup;
}

TEST_CASE("robust kd-tree walks never leak where nested splits meet at a vertex", "[stability]") {
    // The entry/exit-point walk's weak spot: planes through one vertex on two or three axes,
    // nested in the tree, crossed by a ray from the exact centre at one t. Every vertex and every
    // corner of a split's face in its cell, at several scales of the direction (exact), on
    // jittered spheres; the first mesh is one the walk once lost rays on.
    const std::array<std::array<double, 4>, 4> meshes{
        {{2, 8, 12, 0.2}, {5, 16, 24, 0.1}, {7, 12, 16, 0.45}, {11, 24, 32, 0.3}}};
    for (const auto& m : meshes) {
        const rtlab::IndexedMesh im = rtlab::perturbed_sphere_mesh(
            static_cast<std::uint64_t>(m[0]), static_cast<std::uint32_t>(m[1]),
            static_cast<std::uint32_t>(m[2]), m[3]);
        rtlab::TriangleMesh mesh;
        mesh.positions = im.vertices;
        mesh.triangles = im.faces;
        const rtlab::Scene scene = rtlab::stab::mesh_scene(mesh);
        for (const char* spec :
             {"brute", "bvh8", "kdtree:sah", "kdtree:sah,perfect=0", "kdtree:sah,traversal=tvalue",
              "kdtree:median", "kdtree:median,traversal=tvalue"}) {
            const rtlab::SceneTracer tracer(scene, robust_setup(spec, "watertight"));
            std::vector<rtlab::Vec3f> targets = mesh.positions;
            const rtlab::AnyAccel& accel = rtlab::stab::triangle_accel(tracer);
            for (const auto& p : rtlab::stab::structure_planes(accel)) {
                for (int c = 0; c < 4; ++c) {
                    rtlab::Vec3f q = p.face.lo;
                    const std::uint32_t a1 = (p.axis + 1) % 3, a2 = (p.axis + 2) % 3;
                    q[a1] = (c & 1) != 0 ? p.face.hi[a1] : p.face.lo[a1];
                    q[a2] = (c & 2) != 0 ? p.face.hi[a2] : p.face.lo[a2];
                    targets.push_back(q);
                }
            }
            std::vector<rtlab::Rayf> rays;
            for (const rtlab::Vec3f& v : targets) {
                for (int k = -2; k <= 2; ++k) {
                    rtlab::Rayf r;
                    r.dir = v * std::ldexp(1.0f, k);
                    if (rtlab::is_valid(r)) {
                        rays.push_back(r);
                    }
                }
            }
            std::vector<rtlab::Hit> hits(rays.size());
            tracer.intersect(rays, hits);
            std::size_t leaks = 0;
            for (const rtlab::Hit& h : hits) {
                leaks += h.valid() ? 0 : 1;
            }
            CAPTURE(m[0], m[1], m[2], m[3], spec, rays.size());
            CHECK(leaks == 0);
        }
    }
}

TEST_CASE("robust kd-tree walks lose no adversarial ray with a non-watertight method",
          "[stability]") {
    // A method that leaks by itself reaches hits the watertight one does not: Moller-Trumbore on
    // adversarial meshes and rays where the walk that lowered nested crossings' t lost rays (20,000
    // rays each: 31 and 32 with perfect=0, 2 with perfect splits). The oracle is exact: a ray is
    // lost when the method alone hits a triangle that the exact ray meets, yet the kd-tree returns
    // no hit.
    using M = rtlab::MollerTrumbore<float>;
    for (const auto& [seed, k] :
         std::array<std::pair<std::uint64_t, std::size_t>, 3>{{{6, 0}, {24, 2}, {14, 5}}}) {
        const rtlab::Scene scene = rtlab::stab::adversarial_scenes(seed).at(k);
        const rtlab::TriangleMesh& mesh = scene.meshes[0].mesh;
        for (const char* spec : {"kdtree:sah", "kdtree:sah,perfect=0",
                                 "kdtree:sah,traversal=tvalue", "kdtree:median"}) {
            const rtlab::SceneTracer tracer(scene, robust_setup(spec, "moller_trumbore"));
            const rtlab::AnyAccel& accel = rtlab::stab::triangle_accel(tracer);
            const std::vector<rtlab::Rayf> rays =
                rtlab::stab::adversarial_rays(mesh, accel, 20000, seed * 16 + k);
            std::vector<rtlab::Hit> hits(rays.size());
            tracer.intersect(rays, hits);
            rtlab::stab::LeakTally tally;
            rtlab::stab::tally_leaks<M>(mesh, rays, hits, tally);
            CAPTURE(seed, k, spec, tally.leaks);
            CHECK(tally.leaks > 0);  // the method leaks by itself here: the rays reach its rounding
            CHECK(tally.lost == 0);
        }
    }
}

TEST_CASE("robust traversal of diagonal-slab nodes is the box traversal", "[stability]") {
    // The slabs' weak spot would be a slab rounded inside the exact hull; robust traversal does
    // not test them, so it must visit the same boxes in the same order: the same closest hit,
    // bit for bit, as the same tree without slabs, on the adversarial rays of both meshes.
    for (const std::size_t k : {std::size_t{0}, std::size_t{4}}) {
        const rtlab::Scene scene = rtlab::stab::adversarial_scenes(3).at(k);
        std::vector<std::vector<rtlab::Hit>> answers;
        std::vector<rtlab::Rayf> rays;
        for (const char* spec : {"bvh16", "bvh16,bounds=dop14"}) {
            const rtlab::SceneTracer tracer(scene, robust_setup(spec, "moller_trumbore"));
            if (rays.empty()) {
                const rtlab::AnyAccel& accel = rtlab::stab::triangle_accel(tracer);
                rays = rtlab::stab::adversarial_rays(scene.meshes[0].mesh, accel, 20000, 7);
            }
            answers.emplace_back(rays.size());
            tracer.intersect(rays, answers.back());
        }
        std::size_t differ = 0, hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const rtlab::Hit &a = answers[0][i], &b = answers[1][i];
            hits += a.valid() ? 1 : 0;
            differ += (a.prim != b.prim || (a.valid() && a.t != b.t)) ? 1 : 0;
        }
        CAPTURE(k, rays.size(), hits);
        CHECK(hits > rays.size() / 2);
        CHECK(differ == 0);
    }
}

TEST_CASE("robust grid walks lose no ray from far origins", "[stability]") {
    // The 3D-DDA's weak spot: from far away its entry point and crossing times round by ulps of
    // |org|, many cells' worth. Rays from 10^2 to 10^11 radii (past 10^10 cells the walk visits
    // every cell) towards vertices, cell corners and cell edges of the built grid; the oracle is
    // exact: a ray is lost when the method alone hits a triangle that the exact ray meets, yet the
    // grid returns no hit.
    using M = rtlab::Watertight<float>;
    for (const auto& [seed, rings, segments, jitter] :
         std::array<std::tuple<std::uint64_t, std::uint32_t, std::uint32_t, double>, 2>{
             {{3, 12, 16, 0.3}, {13, 24, 32, 0.45}}}) {
        const rtlab::IndexedMesh im = rtlab::perturbed_sphere_mesh(seed, rings, segments, jitter);
        rtlab::TriangleMesh mesh;
        mesh.positions = im.vertices;
        mesh.triangles = im.faces;
        const rtlab::Scene scene = rtlab::stab::mesh_scene(mesh);
        for (const char* spec : {"grid:uniform", "grid:uniform,density=8", "grid:two_level"}) {
            const rtlab::SceneTracer tracer(scene, robust_setup(spec, "watertight"));
            const rtlab::AnyAccel& accel = rtlab::stab::triangle_accel(tracer);
            const std::vector<rtlab::stab::StructurePlane> planes =
                rtlab::stab::structure_planes(accel);
            REQUIRE(!planes.empty());
            rtlab::Sampler rng(seed, 77);
            std::vector<rtlab::Rayf> rays;
            while (rays.size() < 3000) {
                rtlab::Rayf r;
                r.org = rtlab::Vec3f(rng.unit() * std::pow(10.0, rng.uniform(2, 11)));
                rtlab::Vec3f target = mesh.positions[rng.index(mesh.positions.size())];
                if (rays.size() % 3 != 0) {  // a corner (or an edge point) of a cell face
                    const auto& p = planes[rng.index(planes.size())];
                    target = p.face.lo;
                    for (const std::uint32_t a : {(p.axis + 1) % 3, (p.axis + 2) % 3}) {
                        const float u = static_cast<float>(
                            rays.size() % 3 == 1 ? rng.index(2) : rng.uniform(0, 1));
                        target[a] = p.face.lo[a] + u * (p.face.hi[a] - p.face.lo[a]);
                    }
                }
                r.dir = target - r.org;
                if (rtlab::is_valid(r)) {
                    rays.push_back(r);
                }
            }
            std::vector<rtlab::Hit> hits(rays.size());
            tracer.intersect(rays, hits);
            rtlab::stab::LeakTally tally;
            rtlab::stab::tally_leaks<M>(mesh, rays, hits, tally);
            std::size_t must_hit = 0;
            for (const rtlab::Rayf& r : rays) {
                must_hit += rtlab::stab::method_alone<M>(mesh, r).exact ? 1 : 0;
            }
            CAPTURE(seed, rings, segments, jitter, spec, rays.size(), tally.leaks, tally.outside);
            CHECK(must_hit > rays.size() / 3);  // many rays must hit: the test has teeth
            CHECK(tally.lost == 0);
        }
    }
}

TEST_CASE("stability intgrid: lattice rays never leak with watertight + robust", "[stability]") {
    const std::vector<Row> rows = rtlab::stab::run_intgrid({}, watertight_robust_only());
    log_failures(rows);
    REQUIRE(rows.size() == rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
}

TEST_CASE("stability intgrid, every method, structure and traversal", "[.stability-full]") {
    const std::vector<Row> rows = rtlab::stab::run_intgrid({});
    log_failures(rows);
    REQUIRE(rows.size() == (4 * 2 + 1) * rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
    CHECK(require_exact_tight(rows) == rtlab::stab::leak_case_specs().size());
}

/// Invalid rays never traverse; robust degenerate rays agree with the box-free loop.
static void require_degenerate(const std::vector<Row>& rows) {
    std::size_t rejected = 0, rays = 0;
    for (const Row& r : rows) {
        CAPTURE(r.subject, r.failures, r.note);
        rays += r.rays;
        if (starts_with(r.subject, "rejected: ")) {
            CHECK(r.failures == 0);
            CHECK(r.note.find("nodes visited 0, traversals started 0") != std::string::npos);
            ++rejected;
        } else if (ends_with(r.subject, " robust")) {
            CHECK(r.failures == 0);
        }
    }
    CHECK(rejected == 5);
    CHECK(rays >= 10000);
}

TEST_CASE("stability degenerate: invalid rays rejected before any node, degenerate ones agree",
          "[stability]") {
    rtlab::stab::Selection sel;
    sel.plain = false;
    const std::vector<Row> rows = rtlab::stab::run_degenerate({}, sel);
    log_failures(rows);
    CHECK(rows.size() == 5 + 5);
    require_degenerate(rows);
}

TEST_CASE("stability degenerate, plain and robust", "[.stability-full]") {
    const std::vector<Row> rows = rtlab::stab::run_degenerate({});
    log_failures(rows);
    CHECK(rows.size() == 2 * 5 + 5);
    require_degenerate(rows);
}

TEST_CASE("stability grazing: exact answers; the robust slab test never misses", "[stability]") {
    const std::vector<Row> rows = rtlab::stab::run_grazing({});
    log_failures(rows);
    // 3 sphere, 4 triangle and 2 aabb methods, float and double.
    REQUIRE(rows.size() == 18);
    for (const Row& r : rows) {
        CAPTURE(r.subject, r.precision, r.note);
        CHECK(r.rays == 10000);
        CHECK(r.failures <= r.rays);
        if (r.subject == "aabb/slabs_robust") {
            CHECK(r.note.find(" 0 false misses") != std::string::npos);
        }
        if (r.subject != "triangle/segura_feito") {
            CHECK(!std::isnan(r.median_rel_t_err));
        }
    }
}

/// Every robust row agrees with the box-free loop.
static void require_structures(const std::vector<Row>& rows, std::size_t min_rays) {
    for (const Row& r : rows) {
        CAPTURE(r.case_name, r.subject, r.note);
        CHECK(r.rays >= min_rays);
        if (ends_with(r.subject.substr(0, r.subject.find(',')), " robust")) {
            CHECK(r.failures == 0);
        }
    }
}

TEST_CASE(
    "stability structures: every structure with robust traversal agrees with a box-free "
    "loop",
    "[stability]") {
    rtlab::stab::Selection sel;
    sel.plain = false;
    sel.brute = false;
    sel.split_rays = true;
    const std::vector<Row> rows = rtlab::stab::run_structures({}, sel);
    log_failures(rows);
    REQUIRE(rows.size() == 4 * (rtlab::accel_registry().size() - 1));
    std::size_t rays_per_structure = 0;
    for (const Row& r : rows) {
        rays_per_structure += r.subject.rfind("bvh:binned ", 0) == 0 ? r.rays : 0;
    }
    CHECK(rays_per_structure >= 9996);
    require_structures(rows, 2496);
}

TEST_CASE("stability structures, plain and robust, brute force included", "[.stability-full]") {
    const std::vector<Row> rows = rtlab::stab::run_structures({});
    log_failures(rows);
    REQUIRE(rows.size() == 4 * 2 * rtlab::accel_registry().size());
    require_structures(rows, 9996);
}
