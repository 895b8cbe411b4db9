// Slurm job-array and merge scripts.
#include "sweep/slurm.h"

#include <fmt/format.h>

namespace rtlab::sweep {

std::string shell_quote(const std::string& s) {
    std::string q(1, '\'');
    for (const char c : s) {
        if (c == '\'') {
            q.append("'\\''");
        } else {
            q.push_back(c);
        }
    }
    q.push_back('\'');
    return q;
}

std::string array_range(const std::vector<std::size_t>& shards,
                        std::size_t total,
                        int max_parallel) {
    std::string r;
    if (shards.size() == total && total > 0) {
        r = fmt::format("0-{}", total - 1);
    } else {
        for (const std::size_t s : shards) {
            r += fmt::format("{}{}", r.empty() ? "" : ",", s);
        }
    }
    if (max_parallel > 0) {
        r += fmt::format("%{}", max_parallel);
    }
    return r;
}

namespace {

std::string common_headers(const SlurmOptions& o) {
    std::string h;
    if (!o.partition.empty()) {
        h += fmt::format("#SBATCH --partition={}\n", o.partition);
    }
    if (!o.account.empty()) {
        h += fmt::format("#SBATCH --account={}\n", o.account);
    }
    return h;
}

}  // namespace

std::string array_script(const Planned& p,
                         const SlurmOptions& o,
                         const std::vector<std::size_t>& shards) {
    const std::string dir = std::filesystem::absolute(p.dir).string();
    std::string s = "#!/bin/bash\n";
    s += fmt::format("# rtlab sweep '{}': one array task per shard ({} shards, {} cases).\n",
                     p.sweep.name, p.shards.size(), p.cases.size());
    s += fmt::format("#SBATCH --job-name=rtlab-sweep-{}\n", p.sweep.name);
    s += fmt::format("#SBATCH --array={}\n", array_range(shards, p.shards.size(), o.max_parallel));
    s += "#SBATCH --ntasks=1\n";
    s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
    s += fmt::format("#SBATCH --output={}/slurm/shard-%a.out\n", dir);
    if (!o.time.empty()) {
        s += fmt::format("#SBATCH --time={}\n", o.time);
    }
    if (o.exclusive) {
        s += "#SBATCH --exclusive\n";
    }
    s += common_headers(o);
    s += "set -eu\n";
    s += "# The shard's threads are the allocation's cores (rtlab reads SLURM_CPUS_PER_TASK);\n";
    s += "# srun binds the task to them so shards on one node do not disturb each other.\n";
    s += fmt::format(
        "exec srun --ntasks=1 --cpu-bind=cores {} sweep run {} -o {} --shard "
        "\"$SLURM_ARRAY_TASK_ID\" --cpus \"${{SLURM_CPUS_PER_TASK:-1}}\"\n",
        shell_quote(o.rtlab), shell_quote(dir + "/sweep.json"), shell_quote(dir));
    return s;
}

std::string merge_script(const Planned& p, const SlurmOptions& o) {
    const std::string dir = std::filesystem::absolute(p.dir).string();
    std::string s = "#!/bin/bash\n";
    s += fmt::format(
        "# rtlab sweep '{}': merges the shards once the array has ended (afterany), reports\n"
        "# missing or failed cases, and builds the report.\n",
        p.sweep.name);
    s += fmt::format("#SBATCH --job-name=rtlab-sweep-{}-merge\n", p.sweep.name);
    s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
    s += fmt::format("#SBATCH --output={}/slurm/merge.out\n", dir);
    s += common_headers(o);
    s += fmt::format("{} sweep merge {} -o {}\nstatus=$?\n", shell_quote(o.rtlab), shell_quote(dir),
                     shell_quote(dir + "/merged"));
    if (!o.report.empty()) {
        s += fmt::format(
            "if command -v python3 >/dev/null && [ -f {0} ]; then\n"
            "    python3 {0} --sweep {1} --out {2} --plots {3} || status=1\n"
            "fi\n",
            shell_quote(o.report), shell_quote(dir + "/merged.json"),
            shell_quote(dir + "/report.md"), shell_quote(dir + "/plots"));
    }
    s += "exit $status\n";
    return s;
}

}  // namespace rtlab::sweep
