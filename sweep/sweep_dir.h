#pragma once
// A sweep folder DIR: sweep.json (the sweep as planned, scene paths resolved through base_dir),
// plan.json (the shard count), results/shard-NNNN.jsonl (one JSON line per finished case of a
// shard; every write replaces the whole file atomically, so a shard file is complete or absent),
// logs/ (output of locally run shards) and slurm/ (job scripts and their output).

#include "sweep/plan.h"
#include "sweep/sweep_file.h"

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtlab::sweep {

/// A sweep with its cases and shards, bound to its folder.
struct Planned {
    std::filesystem::path dir;
    SweepFile sweep;
    std::vector<Case> cases;
    std::vector<std::vector<std::size_t>> shards;  ///< case indices per shard
};

/// Loads FILE, validates and expands it, and binds it to DIR: a new DIR gets sweep.json and
/// plan.json (unless `write` is false: dry runs) once every case passed check_cases (each scene
/// made once); an existing one must hold the same sweep (and, when `shards` is not 0, the same
/// shard count), else rtlab::Error. Nothing is written before validation passed.
Planned plan_into(const std::filesystem::path& file,
                  const std::filesystem::path& dir,
                  std::size_t shards,
                  bool write = true);

/// Opens an existing sweep folder (status, merge); rtlab::Error when it is not one.
Planned open_dir(const std::filesystem::path& dir);

/// The result file of shard k.
std::filesystem::path shard_file(const std::filesystem::path& dir, std::size_t k);

/// The lines of one shard file (none when it is absent); rtlab::Error naming file and line for a
/// line that is not a JSON object with a "case" id.
std::vector<nlohmann::json> read_shard_file(const std::filesystem::path& file);

/// Every recorded result of the folder by case id (a "done" line wins over a "failed" one).
std::map<std::string, nlohmann::json> read_results(const std::filesystem::path& dir);

/// Counts of a sweep folder.
struct Status {
    std::size_t done = 0;
    std::size_t failed = 0;
    std::size_t missing = 0;
    std::vector<std::size_t> failed_cases;   ///< case indices
    std::vector<std::size_t> missing_cases;  ///< case indices
};

/// Which cases of `p` are done, failed or missing, given `results` (from read_results).
Status status_of(const Planned& p, const std::map<std::string, nlohmann::json>& results);

}  // namespace rtlab::sweep
