// rtlab sweep: experiment sweeps (docs/sweeps.md). `plan`, `status` and `merge` live here; `run`
// in cmd_sweep_run.cpp, `submit` in cmd_sweep_submit.cpp; the library in sweep/.
#include "apps/commands.h"
#include "apps/sweep_commands.h"
#include "base/error.h"
#include "sweep/merge.h"
#include "sweep/sweep_dir.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

namespace rtlab::app {

namespace {

struct PlanArgs {
    std::string file;
    std::size_t shards = 0;
    bool json = false;
};

std::string methods_text(const std::string& m) {
    return m.empty() ? "default" : m;
}

int run_plan(const PlanArgs& a) {
    // Planning writes nothing: the folder is only a name here.
    const sweep::Planned p = sweep::plan_into(a.file, "", a.shards, false);
    if (a.json) {
        nlohmann::json j;
        j["sweep"] = p.sweep.name;
        j["cases"] = nlohmann::json::array();
        for (std::size_t k = 0; k < p.shards.size(); ++k) {
            for (const std::size_t i : p.shards[k]) {
                const sweep::Case& c = p.cases[i];
                j["cases"].push_back({{"case", c.id},
                                      {"index", c.index},
                                      {"shard", k},
                                      {"type", sweep::to_string(c.type)},
                                      {"scene", sweep::scene_label(p.sweep, c)},
                                      {"spec", c.spec},
                                      {"methods", methods_text(c.methods)},
                                      {"threads", c.threads},
                                      {"kind", c.kind}});
            }
        }
        std::cout << j.dump(1) << "\n";
        return 0;
    }
    const sweep::SweepFile& s = p.sweep;
    std::size_t renders = 0;
    std::size_t crosschecks = 0;
    for (const sweep::Case& c : p.cases) {
        renders += c.type == sweep::CaseType::render ? 1 : 0;
        crosschecks += c.type == sweep::CaseType::crosscheck ? 1 : 0;
    }
    std::cout << fmt::format(
        "sweep '{}': {} cases = {} scenes x {} specs x {} methods x {} thread counts x {} ray "
        "kinds{}{}; {} rays per kind, repeat {}, seed {}; {} shards\n",
        s.name, p.cases.size(), s.scenes.size(), s.specs.size(), s.methods.size(), s.threads.size(),
        s.kinds.size(), renders > 0 ? fmt::format(" + {} renders", renders) : "",
        crosschecks > 0 ? fmt::format(" + {} cross-checks", crosschecks) : "", s.ray_count,
        s.repeat, s.seed, p.shards.size());
    for (std::size_t k = 0; k < p.shards.size(); ++k) {
        std::cout << fmt::format("shard {}: {} cases\n", k, p.shards[k].size());
        for (const std::size_t i : p.shards[k]) {
            const sweep::Case& c = p.cases[i];
            std::cout << fmt::format("  {} {:>5} {:<24} {:<44} {:<12} {:>2} {}\n", c.id, c.index,
                                     sweep::scene_label(s, c), c.spec, methods_text(c.methods),
                                     c.threads, c.kind);
        }
    }
    return 0;
}

void print_case(const sweep::Planned& p, std::size_t i, const std::string& tail) {
    const sweep::Case& c = p.cases[i];
    std::cout << fmt::format("  {} {} {} {} {}{}\n", c.id, sweep::scene_label(p.sweep, c), c.spec,
                             methods_text(c.methods), c.kind, tail);
}

int run_status(const std::string& dir, bool json) {
    const sweep::Planned p = sweep::open_dir(dir);
    const auto results = sweep::read_results(dir);
    const sweep::Status st = sweep::status_of(p, results);
    if (json) {
        nlohmann::json j;
        j["sweep"] = p.sweep.name;
        j["total"] = p.cases.size();
        j["done"] = st.done;
        j["failed"] = st.failed;
        j["missing"] = st.missing;
        j["failed_cases"] = nlohmann::json::array();
        for (const std::size_t i : st.failed_cases) {
            j["failed_cases"].push_back(
                {{"case", p.cases[i].id}, {"error", results.at(p.cases[i].id).value("error", "")}});
        }
        j["missing_cases"] = nlohmann::json::array();
        for (const std::size_t i : st.missing_cases) {
            j["missing_cases"].push_back(p.cases[i].id);
        }
        std::cout << j.dump(1) << "\n";
        return 0;
    }
    std::cout << fmt::format("sweep '{}' in {}: {} cases: {} done, {} failed, {} missing\n",
                             p.sweep.name, dir, p.cases.size(), st.done, st.failed, st.missing);
    for (std::size_t k = 0; k < p.shards.size(); ++k) {
        std::size_t done = 0;
        std::size_t failed = 0;
        for (const std::size_t i : p.shards[k]) {
            const auto it = results.find(p.cases[i].id);
            if (it != results.end()) {
                (it->second.value("status", "") == "done" ? done : failed) += 1;
            }
        }
        std::cout << fmt::format("  shard {}: {} cases: {} done, {} failed, {} missing\n", k,
                                 p.shards[k].size(), done, failed,
                                 p.shards[k].size() - done - failed);
    }
    if (!st.failed_cases.empty()) {
        std::cout << "failed:\n";
        for (const std::size_t i : st.failed_cases) {
            print_case(p, i, fmt::format(": {}", results.at(p.cases[i].id).value("error", "?")));
        }
    }
    if (!st.missing_cases.empty()) {
        std::cout << "missing:\n";
        for (const std::size_t i : st.missing_cases) {
            print_case(p, i, "");
        }
    }
    return 0;
}

int run_merge(const std::string& dir, std::string table) {
    const sweep::Planned p = sweep::open_dir(dir);
    if (table.empty()) {
        table = (std::filesystem::path(dir) / "merged").string();
    }
    const sweep::MergeOutcome m = sweep::merge_results(p, table);
    std::cout << fmt::format("merged {} of {} cases ({} done, {} failed) into {} and {}\n",
                             m.status.done + m.status.failed, p.cases.size(), m.status.done,
                             m.status.failed, m.csv.string(), m.json.string());
    if (m.status.missing > 0) {
        std::string ids;
        for (std::size_t n = 0; n < std::min<std::size_t>(5, m.status.missing_cases.size()); ++n) {
            ids += fmt::format(" {}", p.cases[m.status.missing_cases[n]].id);
        }
        std::cerr << fmt::format(
            "rtlab sweep merge: {} cases missing (first:{}); run or submit the sweep again to "
            "finish them (rtlab sweep status {})\n",
            m.status.missing, ids, dir);
        return 3;
    }
    return 0;
}

}  // namespace

Command add_sweep(CLI::App& root) {
    CLI::App* sweep = root.add_subcommand(
        "sweep",
        "Experiment sweeps: scenes x structure specs (with parameter lists) x methods x ray kinds "
        "x threads from one JSON file, run here or as a Slurm job array (docs/sweeps.md)");
    sweep->require_subcommand(1);

    auto plan = std::make_shared<PlanArgs>();
    CLI::App* plan_cmd = sweep->add_subcommand(
        "plan", "Validate a sweep file and print its cases (stable ids) and shards");
    plan_cmd->add_option("file", plan->file, "Sweep file (JSON, docs/sweeps.md)")->required();
    plan_cmd->add_option("--shards", plan->shards,
                         "Number of shards (default: one per scene; cases of a scene stay "
                         "together where possible)");
    plan_cmd->add_flag("--json", plan->json, "Print the cases as JSON");

    auto status_dir = std::make_shared<std::string>();
    auto status_json = std::make_shared<bool>(false);
    CLI::App* status_cmd =
        sweep->add_subcommand("status", "List a sweep folder's done, failed and missing cases");
    status_cmd->add_option("dir", *status_dir, "Sweep folder (-o of run or submit)")->required();
    status_cmd->add_flag("--json", *status_json, "Print as JSON");

    auto merge_dir = std::make_shared<std::string>();
    auto merge_table = std::make_shared<std::string>();
    CLI::App* merge_cmd = sweep->add_subcommand(
        "merge",
        "Merge a sweep folder's shard files into TABLE.csv and TABLE.json (plan order); exit 3 "
        "and list missing cases when some have no result");
    merge_cmd->add_option("dir", *merge_dir, "Sweep folder")->required();
    merge_cmd->add_option("-o,--output", *merge_table,
                          "Table path without suffix (default DIR/merged)");

    const SweepCommand run = add_sweep_run(*sweep);
    const SweepCommand submit = add_sweep_submit(*sweep);
    return {sweep, [=] {
                if (plan_cmd->parsed()) {
                    return run_plan(*plan);
                }
                if (status_cmd->parsed()) {
                    return run_status(*status_dir, *status_json);
                }
                if (merge_cmd->parsed()) {
                    return run_merge(*merge_dir, *merge_table);
                }
                if (run.sub->parsed()) {
                    return run.run();
                }
                if (submit.sub->parsed()) {
                    return submit.run();
                }
                return 2;
            }};
}

}  // namespace rtlab::app
