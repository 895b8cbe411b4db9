#pragma once
// Slurm job scripts for a sweep folder: one job array (a task per shard, each running
// `rtlab sweep run DIR/sweep.json -o DIR --shard $SLURM_ARRAY_TASK_ID` with the allocation's
// cores, bound) and a merge job meant to depend on it with afterany (an afterok dependency never
// fires when a task fails), which merges, reports missing cases and builds the report.

#include "sweep/sweep_dir.h"

#include <string>
#include <vector>

namespace rtlab::sweep {

/// sbatch settings of a submission.
struct SlurmOptions {
    std::string partition;   ///< --partition (empty: the cluster's default)
    std::string account;     ///< --account (empty: the user's default)
    std::string time;        ///< --time per array task (empty: the partition's default)
    int max_parallel = 0;    ///< %K of --array (0: no limit)
    int cpus_per_task = 1;   ///< --cpus-per-task of every array task
    bool exclusive = false;  ///< --exclusive: whole nodes, for undisturbed timings
    std::string rtlab;       ///< absolute path of the rtlab executable
    std::string report;      ///< bench/report.py to run after the merge ("" : none)
};

/// The --array value for the shards to run: "0-(N-1)" when all N run, else a list; "%K" added.
std::string array_range(const std::vector<std::size_t>& shards,
                        std::size_t total,
                        int max_parallel);

/// The array job's script.
std::string array_script(const Planned& p,
                         const SlurmOptions& o,
                         const std::vector<std::size_t>& shards);

/// The merge job's script.
std::string merge_script(const Planned& p, const SlurmOptions& o);

/// Single-quotes s for a POSIX shell.
std::string shell_quote(const std::string& s);

}  // namespace rtlab::sweep
