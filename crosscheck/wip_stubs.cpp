// TEMPORARY during the foundation work: each function moves to its <kind>_check.cpp.
#include <stdexcept>

#include "crosscheck/checks.h"

namespace rtlab::xcheck {
#define RTLAB_WIP(kind)                                                     \
    std::vector<std::string> kind##_methods() { return {}; }               \
    std::vector<Row> check_##kind##s(const Options&) {                      \
        throw std::runtime_error("crosscheck for " #kind " is not written yet"); \
    }
RTLAB_WIP(triangle)
RTLAB_WIP(polygon)
RTLAB_WIP(aabb)
RTLAB_WIP(obb)
RTLAB_WIP(sphere)
RTLAB_WIP(implicit)
}  // namespace rtlab::xcheck
