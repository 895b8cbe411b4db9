#pragma once
// The stability report: every case's rows as markdown (docs/stability.md) or JSON, with a header
// naming the command, git revision, compiler and CPU, so figures can be traced to their run.

#include "stability/stability.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace rtlab::stab {

/// Where the figures come from.
struct ReportHeader {
    std::string command;   ///< the command line that produced the report
    std::string revision;  ///< git revision (the caller's; "unknown" when not given)
    std::string compiler;  ///< e.g. "g++ 12.2.0, release" (see compiler_description)
    std::string cpu;       ///< e.g. "AMD EPYC 7B13" (base/host.h cpu_model)
    Options options;       ///< rays and seed of the run
};

/// One case's rows with its description and wall time.
struct CaseResult {
    std::string name;         ///< the case's name
    std::string description;  ///< the case's one sentence
    std::vector<Row> rows;    ///< what the case returned
    double seconds = 0;       ///< wall time of the case's run
};

/// The compiler and build type this binary was built with.
std::string compiler_description();

/// The report as markdown: a header, then per case a table of subject, precision, rays, failures
/// (kind), max/median relative t error, ns/ray and note. NaN figures print as "-".
std::string to_markdown(const ReportHeader& header, std::span<const CaseResult> results);

/// The same report as one JSON object {"header": {...}, "cases": [{name, description, seconds,
/// rows: [...]}]}; NaN figures become null.
std::string to_json(const ReportHeader& header, std::span<const CaseResult> results);

/// Writes text to file completely or not at all (temporary file, then rename); throws
/// rtlab::Error naming the file.
void write_report(const std::filesystem::path& file, const std::string& text);

}  // namespace rtlab::stab
