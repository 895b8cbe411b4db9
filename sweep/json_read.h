#pragma once
// Reading sweep-file values with one-line errors naming the place ("sweep.json: rays.count: ...").
// Internal to sweep/.

#include "base/error.h"

#include <cstdint>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtlab::sweep::detail {

using ojson = nlohmann::ordered_json;

[[noreturn]] inline void fail(const std::string& where, const std::string& what) {
    throw Error(where + ": " + what);
}

inline std::int64_t get_int(const ojson& v,
                            const std::string& where,
                            std::int64_t lo,
                            std::int64_t hi) {
    if (!v.is_number_integer() || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi) {
        fail(where, fmt::format("expected a whole number in [{}, {}], got {}", lo, hi, v.dump()));
    }
    return v.get<std::int64_t>();
}

inline bool get_bool(const ojson& v, const std::string& where) {
    if (!v.is_boolean()) {
        fail(where, fmt::format("expected true or false, got {}", v.dump()));
    }
    return v.get<bool>();
}

inline std::string get_string(const ojson& v, const std::string& where) {
    if (!v.is_string() || v.get<std::string>().empty()) {
        fail(where, fmt::format("expected a non-empty string, got {}", v.dump()));
    }
    return v.get<std::string>();
}

// A list or a single value, as a list.
inline std::vector<ojson> as_list(const ojson& v) {
    if (v.is_array()) {
        return {v.begin(), v.end()};
    }
    return {v};
}

}  // namespace rtlab::sweep::detail
