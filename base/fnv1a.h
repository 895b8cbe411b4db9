#pragma once
// FNV-1a, 64 bits (Fowler, Noll, Vo): a hash stable across runs, builds and machines, for case
// ids and image fingerprints.

#include <cstdint>
#include <string_view>

namespace rtlab {

/// Running FNV-1a hash; feed bytes, read value().
class Fnv1a {
public:
    void add_byte(std::uint8_t b) {
        h_ ^= b;
        h_ *= 1099511628211ull;
    }
    void add(std::string_view text) {
        for (const char c : text) {
            add_byte(static_cast<std::uint8_t>(c));
        }
    }
    /// The four bytes of v, least significant first (the same on every machine).
    void add_u32(std::uint32_t v) {
        for (int b = 0; b < 4; ++b) {
            add_byte(static_cast<std::uint8_t>(v >> (8 * b)));
        }
    }
    std::uint64_t value() const { return h_; }

private:
    std::uint64_t h_ = 14695981039346656037ull;
};

}  // namespace rtlab
