#pragma once
// Seeded numbers, directions and points for the generated shapes and rays of the cross-checks
// and the stability suite. The mapping from the generator's bits to values is our own (the
// standard distributions are implementation-defined), so a set is the same with every standard
// library.

#include "intersect/vec.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace rtlab {

/// Seeded uniform numbers, unit vectors and points in a ball (mt19937_64, 53-bit mantissas).
class Sampler {
public:
    /// Same seed and stream, same sequence; streams of one seed are independent sequences.
    explicit Sampler(std::uint64_t seed, std::uint64_t stream = 0)
        : rng_(seed * 0x9E3779B97F4A7C15ull + stream + 1) {}
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    }
    /// Index in [0, n).
    std::size_t index(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }
    /// Uniform unit vector (rejection from the cube).
    Vec3d unit() {
        for (;;) {
            const Vec3d p{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const double l2 = length_squared(p);
            if (l2 > 1e-4 && l2 <= 1) {
                return p / std::sqrt(l2);
            }
        }
    }
    /// Uniform point in the ball of radius r around the origin.
    Vec3d ball(double r) { return unit() * (r * std::cbrt(uniform(0, 1))); }

private:
    std::mt19937_64 rng_;
};

}  // namespace rtlab
