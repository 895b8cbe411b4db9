#pragma once
// Running one shard of a sweep in this process: each scene is generated once, each ray set made
// once, each structure built once per (spec, methods, threads) and traced for every ray kind.
// After every case the shard's result file is rewritten atomically with every result so far, so
// an interrupted shard leaves a complete file and a re-run skips the cases it holds as done.

#include "sweep/sweep_dir.h"

#include <cstddef>
#include <ostream>

namespace rtlab::sweep {

/// How to run a shard.
struct ShardOptions {
    int cpus = 0;                 ///< threads for cases asking for all (0: every core)
    std::ostream* log = nullptr;  ///< one line per case when given
};

/// What a shard run did.
struct ShardOutcome {
    std::size_t done = 0;     ///< cases measured now
    std::size_t failed = 0;   ///< cases that failed now (recorded with their error)
    std::size_t skipped = 0;  ///< cases already done before
};

/// Runs shard k of p (rtlab::Error when k is not a shard of p).
ShardOutcome run_shard(const Planned& p, std::size_t k, const ShardOptions& opt);

/// Threads "all" means for this process: SLURM_CPUS_PER_TASK under Slurm, else every core TBB
/// sees (the process's affinity mask).
int default_cpus();

}  // namespace rtlab::sweep
