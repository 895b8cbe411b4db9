#pragma once
// Splitting comma-separated option values ("a,b,,c"), shared by the command line and sweep files.

#include <algorithm>
#include <string>
#include <vector>

namespace rtlab {

/// Splits "a,b,,c" into {"a", "b", "c"} (empty items dropped).
inline std::vector<std::string> split_commas(const std::string& s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t end = std::min(s.find(',', start), s.size());
        if (end > start) {
            out.push_back(s.substr(start, end - start));
        }
        start = end + 1;
    }
    return out;
}

}  // namespace rtlab
