// rtlab stability: runs the numerical-stability suite (stability/) and writes its report as
// markdown (docs/stability.md) and/or JSON; --fixture writes the watertightness scene and rays
// so `rtlab trace` can be checked on them.
#include "apps/commands.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/host.h"
#include "base/split.h"
#include "datasets_gen/memory_guard.h"
#include "mesh/mesh_io.h"
#include "stability/fixtures.h"
#include "stability/report.h"
#include "stability/stability.h"
#include "trace/binary_io.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace rtlab::app {

namespace {

struct StabilityArgs {
    std::string cases;
    std::size_t rays = 10000;
    std::uint64_t seed = 1;
    std::string markdown;
    std::string json;
    std::string fixture;
    bool list = false;
    std::uint64_t max_memory_mib = 0;
};

/// Upper bound of the bytes held per ray by the largest case (its ray sets in double and float
/// and the answers of every method). Measured peak growth (RSS at 20,000 against 5,000 rays,
/// release build): about 560 B/ray.
constexpr std::uint64_t stability_bytes_per_ray = 1024;

/// --fixture: the closed perturbed sphere and the rays from inside it, written to dir.
void write_fixture(const std::filesystem::path& dir, const stab::Options& opt) {
    std::filesystem::create_directories(dir);
    const TriangleMesh mesh = stab::watertight_sphere(opt.seed);
    save_mesh(mesh, dir / "sphere.ply");
    save_rays(dir / "inside.rays", stab::inside_rays(mesh, opt.rays, opt.seed));
    std::cerr << fmt::format(
        "rtlab stability: wrote {} (closed perturbed sphere, {} triangles) and {} ({} rays "
        "from inside; every one must hit)\n",
        (dir / "sphere.ply").string(), mesh.triangle_count(), (dir / "inside.rays").string(),
        opt.rays);
}

/// The cases --case names (comma-separated; all when empty), or an Error naming the known ones.
std::vector<const stab::Case*> selected_cases(const std::string& names) {
    std::vector<const stab::Case*> selected;
    if (names.empty()) {
        for (const stab::Case& c : stab::cases()) {
            selected.push_back(&c);
        }
        return selected;
    }
    for (const std::string& name : split_commas(names)) {
        const stab::Case* c = stab::find_case(name);
        if (c == nullptr) {
            std::string known;
            for (const stab::Case& k : stab::cases()) {
                known += (known.empty() ? "" : ", ") + std::string(k.name);
            }
            throw Error("unknown stability case '" + name + "' (known: " + known + ")");
        }
        selected.push_back(c);
    }
    return selected;
}

/// The report's header: the command that reproduces it, revision, compiler and CPU.
stab::ReportHeader report_header(const StabilityArgs& a, const stab::Options& opt) {
    stab::ReportHeader header;
    header.command = fmt::format("rtlab stability --rays {} --seed {}", opt.rays, opt.seed);
    if (!a.cases.empty()) {
        header.command += " --case " + a.cases;
    }
    const char* rev = std::getenv("RTLAB_GIT_REVISION");
    header.revision = rev != nullptr && *rev != '\0' ? rev : "unknown";
    header.compiler = stab::compiler_description();
    header.cpu = cpu_model();
    header.options = opt;
    return header;
}

/// Case i of n run with progress on stderr; adds its failures to total_failures.
stab::CaseResult run_case(const stab::Case& c,
                          std::size_t i,
                          std::size_t n,
                          const stab::Options& opt,
                          std::size_t& total_failures) {
    std::cerr << fmt::format("rtlab stability: [{}/{}] {} ...\n", i + 1, n, c.name);
    const auto t0 = std::chrono::steady_clock::now();
    stab::CaseResult r;
    r.name = std::string(c.name);
    r.description = std::string(c.description);
    r.rows = c.run(opt);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::size_t failures = 0;
    for (const stab::Row& row : r.rows) {
        failures += row.failures;
    }
    total_failures += failures;
    std::cerr << fmt::format("rtlab stability: [{}/{}] {}: {} rows, {} failures, {:.1f} s\n", i + 1,
                             n, c.name, r.rows.size(), failures, r.seconds);
    return r;
}

int run_stability(const StabilityArgs& a) {
    if (a.list) {
        for (const stab::Case& c : stab::cases()) {
            std::cout << fmt::format("{:<14} {}\n", c.name, c.description);
        }
        return 0;
    }
    for (const std::string& out : {a.markdown, a.json}) {
        if (!out.empty()) {
            check_output_path(out);  // before the work, not after it
        }
    }
    gen::check_memory(fmt::format("stability --rays {}", a.rays),
                      gen::saturating_mul(a.rays, stability_bytes_per_ray),
                      gen::memory_limit_mib(a.max_memory_mib));
    stab::Options opt;
    opt.rays = a.rays;
    opt.seed = a.seed;
    if (!a.fixture.empty()) {
        write_fixture(a.fixture, opt);
        return 0;
    }
    const std::vector<const stab::Case*> selected = selected_cases(a.cases);
    const stab::ReportHeader header = report_header(a, opt);
    std::vector<stab::CaseResult> results;
    std::size_t total_failures = 0;
    for (std::size_t i = 0; i < selected.size(); ++i) {
        results.push_back(run_case(*selected[i], i, selected.size(), opt, total_failures));
    }

    const std::string md = stab::to_markdown(header, results);
    if (!a.markdown.empty()) {
        stab::write_report(a.markdown, md);
    }
    if (!a.json.empty()) {
        stab::write_report(a.json, stab::to_json(header, results));
    }
    if (a.markdown.empty() && a.json.empty()) {
        std::cout << md;
    }
    std::cerr << fmt::format("rtlab stability: {} cases, {} failures recorded{}{}\n",
                             results.size(), total_failures,
                             a.markdown.empty() ? "" : ", markdown: " + a.markdown,
                             a.json.empty() ? "" : ", json: " + a.json);
    // A row the suite classifies as a defect of rtlab (not of a method under test) fails the run.
    std::size_t defects = 0;
    for (const stab::CaseResult& r : results) {
        for (const stab::Row& row : r.rows) {
            if (row.defect) {
                std::cerr << fmt::format("rtlab stability: defect: {} | {} | {}\n", row.case_name,
                                         row.subject, row.note);
                ++defects;
            }
        }
    }
    return defects == 0 ? 0 : 1;
}

}  // namespace

Command add_stability(CLI::App& root) {
    auto a = std::make_shared<StabilityArgs>();
    CLI::App* sub = root.add_subcommand(
        "stability",
        "Run the numerical-stability suite (leaks, degenerate and grazing rays, far and small "
        "geometry, self-intersection, ...); prints the markdown report on stdout, or writes it "
        "with "
        "--markdown FILE / --json FILE (scripts/stability regenerates docs/stability.md)");
    sub->add_option("--case", a->cases, "Cases to run, comma-separated (default: all; see --list)");
    sub->add_option("--rays", a->rays, "Rays per subject and precision (default 10000)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
    sub->add_option("--seed", a->seed, "Seed of shapes and rays (default 1)");
    sub->add_option("--max-memory", a->max_memory_mib,
                    "Refuse ray counts whose estimate exceeds this many MiB (default half of RAM)");
    sub->add_option("--markdown", a->markdown, "Write the report as markdown to this file");
    sub->add_option("--json", a->json, "Write the report as JSON to this file");
    sub->add_flag("--list", a->list, "List the cases and exit");
    sub->add_option("--fixture", a->fixture,
                    "Write the watertightness fixture to this folder instead of running: "
                    "sphere.ply (closed perturbed sphere) and inside.rays (--rays rays from "
                    "inside, all must hit)");
    return {sub, [a] { return run_stability(*a); }};
}

}  // namespace rtlab::app
