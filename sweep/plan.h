#pragma once
// A sweep's cases and shards. Trace cases are the product scenes x structures x methods x threads
// x ray kinds, in that order (the last varies fastest); render cases (scenes x structures x AOVs of
// each "renders" entry) and cross-check cases (methods x precisions of each "crosscheck" entry)
// follow. Each has a stable id derived from what it measures, so the same file always gives the
// same ids in the same order. Shards deal cases out so that cases sharing a scene share a shard
// where possible; cross-check cases, which need no scene, form one more group.

#include "sweep/sweep_file.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rtlab::sweep {

/// What a case measures.
enum class CaseType {
    trace,      ///< a ray set through a structure
    render,     ///< an image of a scene through a structure
    crosscheck  ///< one intersection method in one precision against the exact oracle
};

/// One measurement. Trace: a scene, a structure spec, a method list, a thread count and a ray
/// kind. Render: a scene, a spec, an AOV (in `kind`) and the image size. Cross-check: a primitive
/// kind, one method (in `methods`) and a precision (in `kind`).
struct Case {
    std::string id;         ///< 16 hex digits of a hash of everything the case measures
    std::size_t index = 0;  ///< position in plan order
    CaseType type = CaseType::trace;
    std::size_t scene = 0;  ///< index into SweepFile::scenes; scenes.size() for cross-checks
    std::string spec;       ///< canonical structure spec ("" for cross-checks)
    std::string methods;    ///< method list, "" for the families' defaults
    int threads = 0;        ///< requested threads, 0 = all the run has
    std::string kind;       ///< ray kind; AOV (render); precision (cross-check)
    std::size_t entry = 0;  ///< render/cross-check: index into SweepFile::renders/crosschecks
    bool any_hit() const { return type == CaseType::trace && kind == "shadow"; }
};

/// "trace", "render" or "crosscheck".
const char* to_string(CaseType t);

/// The case's scene label, or "-" for a cross-check case.
std::string scene_label(const SweepFile& s, const Case& c);

/// Every case of the sweep in plan order; throws rtlab::Error when two cases are the same.
std::vector<Case> expand_cases(const SweepFile& s);

/// Case indices per shard. shards = 0 gives one shard per scene. With fewer shards than scenes,
/// whole scenes are dealt round robin; with more, each scene gets shards in proportion to its
/// cases and its cases are split into contiguous runs (so builds are shared within a run).
std::vector<std::vector<std::size_t>> deal_shards(const SweepFile& s,
                                                  const std::vector<Case>& cases,
                                                  std::size_t shards);

}  // namespace rtlab::sweep
