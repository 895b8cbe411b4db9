// The numerical-stability suite (stability/): the framework (registry, report writers) and the
// fast part of the watertight, intgrid, degenerate, grazing and structures cases, each with the
// default 10,000 rays. Each asserts the property that must hold (zero leaks for watertight +
// robust traversal, rejection of invalid rays, agreement of every structure with a box-free
// loop, no false misses of the robust slab test) and only records the other failure counts.
#include "stability/stability.h"

#include "accel/any_accel.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "stability/report.h"
#include "support/temp_dir.h"
#include "trace/binary_io.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>

namespace {

using rtlab::stab::Row;

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool starts_with(const std::string& s, const std::string& head) {
    return s.rfind(head, 0) == 0;
}

/// Prints every row with failures, so a failing REQUIRE comes with the whole picture.
void log_failures(const std::vector<Row>& rows) {
    for (const Row& r : rows) {
        if (r.failures > 0) {
            UNSCOPED_INFO(r.case_name << " | " << r.subject << " | " << r.precision << " | "
                                      << r.failures << " " << r.failure_kind << " | " << r.note);
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
    h.cpu = rtlab::stab::cpu_description();
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
    REQUIRE(rows.size() == 4 * 2 * rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
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
    REQUIRE(rows.size() == 4 * 2 * rtlab::stab::leak_case_specs().size());
    CHECK(require_watertight_robust_tight(rows) == rtlab::stab::leak_case_specs().size());
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
