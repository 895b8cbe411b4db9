// rtlab sweep submit --slurm: writes the job-array and merge scripts into DIR/slurm and submits
// them with sbatch (the merge job after the array with afterany); --dry-run prints them instead.
#include "apps/sweep_commands.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "sweep/provenance.h"
#include "sweep/slurm.h"
#include "sweep/sweep_dir.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace rtlab::app {

namespace {

namespace fs = std::filesystem;

struct SubmitArgs {
    std::string file;
    std::string out;
    bool slurm = false;
    bool dry_run = false;
    std::size_t shards = 0;
    sweep::SlurmOptions slurm_opts;
};

// Runs a shell command, returns its stdout; rtlab::Error with its output when it fails.
std::string run_command(const std::string& cmd) {
    FILE* f = popen((cmd + " 2>&1").c_str(), "r");
    if (f == nullptr) {
        throw Error(fmt::format("sweep submit: cannot run {}", cmd));
    }
    std::string out;
    char buf[512];
    while (std::fgets(buf, sizeof buf, f) != nullptr) {
        out += buf;
    }
    const int rc = pclose(f);
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) {
        out.pop_back();
    }
    if (rc != 0) {
        throw Error(fmt::format("sweep submit: `{}` failed: {}", cmd, out));
    }
    return out;
}

std::string job_id(const std::string& parsable) {
    std::string id = parsable.substr(parsable.rfind('\n') + 1);
    id = id.substr(0, id.find(';'));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
        throw Error(fmt::format("sweep submit: sbatch printed no job id: {}", parsable));
    }
    return id;
}

int run_submit(SubmitArgs& a) {
    if (!a.slurm) {
        throw Error("sweep submit: name the scheduler: --slurm (the only one supported)");
    }
    const sweep::Planned p = sweep::plan_into(a.file, a.out, a.shards, !a.dry_run);
    std::vector<std::size_t> pending;
    const auto results = sweep::read_results(p.dir);
    for (std::size_t k = 0; k < p.shards.size(); ++k) {
        for (const std::size_t i : p.shards[k]) {
            const auto it = results.find(p.cases[i].id);
            if (it == results.end() || it->second.value("status", "") != "done") {
                pending.push_back(k);
                break;
            }
        }
    }
    if (pending.empty()) {
        std::cout << fmt::format(
            "sweep '{}': all {} cases are done in {}; nothing to submit "
            "(rtlab sweep merge {})\n",
            p.sweep.name, p.cases.size(), p.dir.string(), p.dir.string());
        return 0;
    }
    sweep::SlurmOptions o = a.slurm_opts;
    o.rtlab = fs::read_symlink("/proc/self/exe").string();
    const fs::path report = fs::path(sweep::source_dir()) / "bench" / "report.py";
    o.report = fs::exists(report) ? report.string() : "";
    const std::string array = sweep::array_script(p, o, pending);
    const std::string merge = sweep::merge_script(p, o);
    const fs::path dir = fs::absolute(p.dir);
    const std::string array_file = (dir / "slurm" / "array.sbatch").string();
    const std::string merge_file = (dir / "slurm" / "merge.sbatch").string();
    const std::string submit_array =
        fmt::format("sbatch --parsable {}", sweep::shell_quote(array_file));
    const std::string submit_merge = fmt::format(
        "sbatch --parsable --dependency=afterany:$ARRAY_JOB {}", sweep::shell_quote(merge_file));
    if (a.dry_run) {
        std::cout << fmt::format("# {}\n{}\n# {}\n{}\n# commands:\nARRAY_JOB=$({})\n{}\n",
                                 array_file, array, merge_file, merge, submit_array, submit_merge);
        return 0;
    }
    fs::create_directories(dir / "slurm");
    write_file_atomically(array_file, array);
    write_file_atomically(merge_file, merge);
    const std::string array_id = job_id(run_command(submit_array));
    const std::string merge_id =
        job_id(run_command(fmt::format("sbatch --parsable --dependency=afterany:{} {}", array_id,
                                       sweep::shell_quote(merge_file))));
    write_file_atomically(dir / "slurm" / "jobs.json",
                          fmt::format("{{\"array\": {}, \"merge\": {}}}\n", array_id, merge_id));
    std::cout << fmt::format(
        "submitted array job {} ({} of {} shards: --array={}) and merge job {} (afterany:{});\n"
        "follow with: squeue -j {},{}   rtlab sweep status {}\n",
        array_id, pending.size(), p.shards.size(),
        sweep::array_range(pending, p.shards.size(), o.max_parallel), merge_id, array_id, array_id,
        merge_id, dir.string());
    return 0;
}

}  // namespace

SweepCommand add_sweep_submit(CLI::App& sweep) {
    auto a = std::make_shared<SubmitArgs>();
    CLI::App* sub = sweep.add_subcommand(
        "submit",
        "Submit a sweep to Slurm: one job array (a task per unfinished shard, each `rtlab sweep "
        "run --shard $SLURM_ARRAY_TASK_ID` with its allocation's cores, bound) and a merge job "
        "after it (afterany) that merges, reports missing cases and builds the report");
    sub->add_option("file", a->file, "Sweep file (JSON, docs/sweeps.md)")->required();
    sub->add_option("-o,--output", a->out,
                    "Sweep folder, on a file system every node sees (default "
                    "out/sweep-<file name>)");
    sub->add_flag("--slurm", a->slurm, "Submit to Slurm with sbatch (the only scheduler)");
    sub->add_option("--shards", a->shards,
                    "Number of shards for a new folder (default: one per scene)");
    sub->add_option("--partition", a->slurm_opts.partition, "sbatch --partition");
    sub->add_option("--account", a->slurm_opts.account, "sbatch --account");
    sub->add_option("--time", a->slurm_opts.time, "Time limit per array task (sbatch --time)");
    sub->add_option("--max-parallel", a->slurm_opts.max_parallel,
                    "At most K array tasks at once (--array=...%K)")
        ->check(CLI::Range(1, 100000));
    sub->add_option("--cpus-per-task", a->slurm_opts.cpus_per_task,
                    "Cores per array task, the shard's thread count (default 1)")
        ->check(CLI::Range(1, 1024));
    sub->add_flag("--exclusive", a->slurm_opts.exclusive,
                  "Whole nodes per task (sbatch --exclusive), for undisturbed timings");
    sub->add_flag("--dry-run", a->dry_run, "Print the scripts and sbatch commands only");
    return {sub, [a] {
                if (a->out.empty()) {
                    a->out = fmt::format("out/sweep-{}", fs::path(a->file).stem().string());
                }
                return run_submit(*a);
            }};
}

}  // namespace rtlab::app
