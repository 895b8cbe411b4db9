// Provenance of results: compile-time revision and version (sweep/CMakeLists.txt), run-time host.
#include "sweep/provenance.h"

#include "base/host.h"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <unistd.h>

namespace rtlab::sweep {

namespace {

std::string env_or(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v != nullptr ? v : fallback;
}

}  // namespace

nlohmann::json run_provenance() {
    nlohmann::json j;
    j["git"] = RTLAB_GIT_REVISION;
    j["version"] = RTLAB_VERSION;
#ifdef NDEBUG
    j["build"] = "release";
#else
    j["build"] = "debug";
#endif
#ifdef __clang__
    j["compiler"] = "clang " __VERSION__;
#else
    j["compiler"] = "g++ " __VERSION__;
#endif
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) != 0) {
        host[0] = '?';
    }
    j["host"] = host;
    j["cpu"] = cpu_model();
    j["slurm_job"] = env_or("SLURM_ARRAY_JOB_ID", env_or("SLURM_JOB_ID", ""));
    j["slurm_task"] = env_or("SLURM_ARRAY_TASK_ID", "");
    return j;
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

double unix_now() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::string source_dir() {
    return RTLAB_SOURCE_DIR;
}

}  // namespace rtlab::sweep
