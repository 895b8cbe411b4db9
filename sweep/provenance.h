#pragma once
// Where and with what a result was measured: git revision, rtlab version and build type,
// compiler, host, CPU model, Slurm job, times.

#include <nlohmann/json.hpp>
#include <string>

namespace rtlab::sweep {

/// Fields that do not change during a run: git, version, build, compiler, host, cpu, and the
/// Slurm job and array task when run under Slurm.
nlohmann::json run_provenance();

/// The current UTC time as ISO 8601 ("2026-11-30T04:12:05Z").
std::string utc_now();

/// The current time in seconds since the epoch.
double unix_now();

/// bench/report.py of the source tree this rtlab was built from (may not exist any more).
std::string source_dir();

}  // namespace rtlab::sweep
