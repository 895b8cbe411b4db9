#pragma once
// The subcommands of `rtlab sweep` (apps/cmd_sweep*.cpp): each registers itself on the `sweep`
// node and returns what to run when it was parsed.

#include <functional>

namespace CLI {
class App;
}

namespace rtlab::app {

/// A `sweep` subcommand: its CLI11 node and its action (returns the exit code).
struct SweepCommand {
    CLI::App* sub;
    std::function<int()> run;
};

/// `rtlab sweep run`: runs a sweep's shards on this machine (or one shard with --shard).
SweepCommand add_sweep_run(CLI::App& sweep);

/// `rtlab sweep submit --slurm`: one Slurm job array plus a merge job.
SweepCommand add_sweep_submit(CLI::App& sweep);

}  // namespace rtlab::app
