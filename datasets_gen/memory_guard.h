#pragma once
// Refusing generator sizes that would not fit in memory, before anything is allocated.

#include <cstdint>
#include <string>
#include <string_view>

namespace rtlab::gen {

/// Half of the physical memory (sysconf pages x page size / 2); 4 GiB when sysconf cannot tell.
[[nodiscard]] std::uint64_t default_memory_limit();

/// The limit a `--max-memory MIB` option asks for: MIB MiB, or default_memory_limit() for 0.
[[nodiscard]] std::uint64_t memory_limit_mib(std::uint64_t mib);

/// Human-readable size with a binary unit, e.g. "3.2 GiB" or "512 B".
[[nodiscard]] std::string format_bytes(std::uint64_t bytes);

/// Throws rtlab::Error "<what>: needs about <estimate>, over the memory limit of <limit> ..." when
/// estimate_bytes > limit_bytes; does nothing otherwise.
void check_memory(std::string_view what, std::uint64_t estimate_bytes, std::uint64_t limit_bytes);

/// a * b, saturating at UINT64_MAX instead of wrapping (for estimates of absurd sizes).
[[nodiscard]] std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b);

/// a + b, saturating at UINT64_MAX.
[[nodiscard]] std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b);

/// base^exp, saturating at UINT64_MAX.
[[nodiscard]] std::uint64_t saturating_pow(std::uint64_t base, int exp);

}  // namespace rtlab::gen
