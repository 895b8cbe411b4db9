#pragma once
// The machine a result was measured on, as reports and provenance records name it.

#include <cstddef>
#include <fstream>
#include <string>

namespace rtlab {

/// The CPU model from /proc/cpuinfo ("model name"), or "unknown".
inline std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) {
                const std::size_t start = line.find_first_not_of(' ', colon + 1);
                return start == std::string::npos ? std::string("unknown") : line.substr(start);
            }
        }
    }
    return "unknown";
}

}  // namespace rtlab
