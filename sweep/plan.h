#pragma once
// A sweep's cases and shards. Cases are the product scenes x structures x methods x threads x
// ray kinds, in that order (the last varies fastest), each with a stable id derived from what it
// measures, so the same file always gives the same ids in the same order. Shards deal cases out
// so that cases sharing a scene share a shard where possible.

#include "sweep/sweep_file.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rtlab::sweep {

/// One measurement: a scene, a structure spec, a method list, a thread count and a ray kind.
struct Case {
    std::string id;         ///< 16 hex digits of a hash of everything the case measures
    std::size_t index = 0;  ///< position in plan order
    std::size_t scene = 0;  ///< index into SweepFile::scenes
    std::string spec;       ///< canonical structure spec
    std::string methods;    ///< method list, "" for the families' defaults
    int threads = 0;        ///< requested threads, 0 = all the run has
    std::string kind;       ///< ray kind
    bool any_hit() const { return kind == "shadow"; }
};

/// Every case of the sweep in plan order; throws rtlab::Error when two cases are the same.
std::vector<Case> expand_cases(const SweepFile& s);

/// Case indices per shard. shards = 0 gives one shard per scene. With fewer shards than scenes,
/// whole scenes are dealt round robin; with more, each scene gets shards in proportion to its
/// cases and its cases are split into contiguous runs (so builds are shared within a run).
std::vector<std::vector<std::size_t>> deal_shards(const SweepFile& s,
                                                  const std::vector<Case>& cases,
                                                  std::size_t shards);

}  // namespace rtlab::sweep
