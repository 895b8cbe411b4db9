// Memory guard for generators: an estimate compared with a limit (default half of physical RAM).
#include "datasets_gen/memory_guard.h"

#include "base/error.h"

#include <cstdio>
#include <limits>
#include <unistd.h>

namespace rtlab::gen {

std::uint64_t default_memory_limit() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page_size <= 0) {
        return 4ull << 30;
    }
    return saturating_mul(static_cast<std::uint64_t>(pages),
                          static_cast<std::uint64_t>(page_size)) /
           2;
}

std::string format_bytes(std::uint64_t bytes) {
    static const char* const units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = static_cast<double>(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 6) {
        value /= 1024.0;
        ++unit;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
    return buf;
}

std::uint64_t memory_limit_mib(std::uint64_t mib) {
    return mib != 0 ? saturating_mul(mib, std::uint64_t{1} << 20) : default_memory_limit();
}

void check_memory(std::string_view what, std::uint64_t estimate_bytes, std::uint64_t limit_bytes) {
    if (estimate_bytes > limit_bytes) {
        throw Error(std::string(what) + ": needs about " + format_bytes(estimate_bytes) +
                    ", over the memory limit of " + format_bytes(limit_bytes) +
                    " (default half of physical memory; raise it with --max-memory)");
    }
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    constexpr std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
    if (a != 0 && b > max / a) {
        return max;
    }
    return a * b;
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    constexpr std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
    return b > max - a ? max : a + b;
}

std::uint64_t saturating_pow(std::uint64_t base, int exp) {
    std::uint64_t r = 1;
    for (int i = 0; i < exp; ++i) {
        r = saturating_mul(r, base);
    }
    return r;
}

}  // namespace rtlab::gen
