#pragma once
// Merging a sweep folder's shard files into one table, in plan order: TABLE.csv (one row per
// case, parameters as p_<key> columns, provenance flattened) and TABLE.json ({"sweep", "cases",
// "missing"}), both written atomically.

#include "sweep/sweep_dir.h"

#include <filesystem>
#include <string>

namespace rtlab::sweep {

/// What a merge wrote and found.
struct MergeOutcome {
    std::filesystem::path csv;
    std::filesystem::path json;
    Status status;
};

/// Merges p's results into `table` (.csv/.json suffixes replaced or added).
MergeOutcome merge_results(const Planned& p, const std::filesystem::path& table);

}  // namespace rtlab::sweep
