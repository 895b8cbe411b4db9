#pragma once
// The text scanning that mesh/format_check.cpp and mesh/format_check_ply.cpp share: tokens,
// numbered lines, strict number parsing and the one-line error. Internal to mesh/.

#include "base/error.h"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::detail::mesh_text {

/// Largest element count we accept: ids are 32-bit and a count this size is a corrupt header.
constexpr std::uint64_t max_count = 0x7fffffffu;

[[noreturn]] inline void fail(const std::string& what, const std::string& problem) {
    throw Error(what + ": " + problem);
}

inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// Splits a line into whitespace-separated tokens.
inline std::vector<std::string_view> tokens_of(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) {
            ++i;
        }
        if (i > start) {
            out.push_back(line.substr(start, i - start));
        }
    }
    return out;
}

/// Iterates lines (without the terminator), counting them from 1.
class LineReader {
public:
    explicit LineReader(std::string_view s) : s_(s) {}
    bool next(std::string_view& line) {
        if (pos_ >= s_.size()) {
            return false;
        }
        const std::size_t end = std::min(s_.find('\n', pos_), s_.size());
        line = s_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++number_;
        return true;
    }
    std::size_t number() const { return number_; }
    std::size_t offset() const { return std::min(pos_, s_.size()); }

private:
    std::string_view s_;
    std::size_t pos_ = 0;
    std::size_t number_ = 0;
};

inline std::optional<double> parse_double(std::string_view t) {
    double v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size()) {
        return std::nullopt;
    }
    return v;
}

inline std::optional<std::int64_t> parse_int(std::string_view t) {
    if (!t.empty() && t.front() == '+') {
        t.remove_prefix(1);
    }
    std::int64_t v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size()) {
        return std::nullopt;
    }
    return v;
}

inline std::string line_at(std::size_t n) {
    return "line " + std::to_string(n);
}

}  // namespace rtlab::detail::mesh_text
