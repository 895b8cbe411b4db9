#pragma once
// The cross-check's ray sets and exact answers (crosscheck/ray_sets.h), computed once per process
// and primitive kind on first use, shared by the intersector and root-finder suites.

#include "bench/benchmarks.h"
#include "crosscheck/ray_sets.h"

#include <cstddef>
#include <cstdint>

namespace rtlab::bench {

/// Seed of every benchmark case set (the seed `rtlab crosscheck` uses by default).
inline constexpr std::uint64_t case_seed = 1;

/// Rays per distribution: 10000 (rates resolved to 1e-4), 1000 with --quick.
inline std::size_t rays_per_set() {
    return quick_mode() ? 1000 : 10000;
}

/// The cases Make(rays_per_set(), case_seed) builds, computed once (the oracle runs here, in
/// parallel, never inside a timed loop).
template <class Shape, xcheck::BenchCases<Shape> (*Make)(std::size_t, std::uint64_t)>
const xcheck::BenchCases<Shape>& cached_cases() {
    static const xcheck::BenchCases<Shape> cases = Make(rays_per_set(), case_seed);
    return cases;
}

/// The float shape in precision T (crosscheck/ray_sets.h).
using xcheck::to_scalar;

}  // namespace rtlab::bench
