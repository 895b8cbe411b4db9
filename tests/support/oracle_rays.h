#pragma once
// How many rays an oracle test traces per method and precision: RTLAB_ORACLE_RAYS if set (the
// asan run uses fewer; scripts/test's release run uses the full count), else 100,000.

#include <cstddef>
#include <cstdlib>
#include <string>

namespace rtlab::test {

/// Ray count for CGAL-oracle tests.
inline std::size_t oracle_rays() {
    if (const char* s = std::getenv("RTLAB_ORACLE_RAYS")) {
        const long long n = std::atoll(s);
        if (n > 0) {
            return static_cast<std::size_t>(n);
        }
    }
    return 100000;
}

}  // namespace rtlab::test
