#pragma once
// Where a secondary ray starts: the hit point moved off the surface by an offset policy, so the
// new ray does not hit the surface it leaves (self-intersection, "surface acne").
//   none:    the hit point itself (the baseline that shows the problem);
//   epsilon: p + epsilon * n, a fixed world-space distance: too small far from the origin, too
//            large for small geometry;
//   ulp:     Wächter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection"
//            (Ray Tracing Gems, ch. 6): each coordinate moves a fixed number of units in the last
//            place along n, so the offset scales with |p|; near the origin, where ULPs vanish, a
//            small fixed offset takes over. Cost: a few integer operations per coordinate.

#include "intersect/vec.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace rtlab {

/// How secondary rays leave a surface.
enum class OffsetPolicy { none, epsilon, ulp };

/// The fixed offset the renderer uses for OffsetPolicy::epsilon unless told otherwise.
inline constexpr float default_offset_epsilon = 1e-4f;

/// Lower-case name of a policy ("none", "epsilon", "ulp").
constexpr std::string_view to_string(OffsetPolicy p) {
    switch (p) {
    case OffsetPolicy::none:
        return "none";
    case OffsetPolicy::epsilon:
        return "epsilon";
    case OffsetPolicy::ulp:
        return "ulp";
    }
    return "?";
}

/// Parses a policy name; throws std::invalid_argument for anything else.
inline OffsetPolicy parse_offset_policy(std::string_view name) {
    for (OffsetPolicy p : {OffsetPolicy::none, OffsetPolicy::epsilon, OffsetPolicy::ulp}) {
        if (to_string(p) == name) {
            return p;
        }
    }
    throw std::invalid_argument("unknown offset policy '" + std::string(name) +
                                "' (none, epsilon, ulp)");
}

namespace detail {

/// Moves x by |ulps| units in the last place, towards +inf for ulps > 0 and towards -inf for
/// ulps < 0 (x finite and not within |ulps| ULPs of zero or of the largest float).
template <class T>
T nudge_ulps(T x, std::int64_t ulps) {
    using Bits = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    const auto bits = std::bit_cast<Bits>(x);
    // As signed integers, IEEE patterns grow with the magnitude: for x < 0 a larger pattern is
    // more negative, so the step's sign flips.
    const auto step = static_cast<Bits>(x < T(0) ? -ulps : ulps);
    return std::bit_cast<T>(static_cast<Bits>(bits + step));
}

}  // namespace detail

/// Origin for a secondary ray leaving surface point p towards the side the unit normal n points
/// to (for a refracted ray entering the surface pass -n). `epsilon` is used by
/// OffsetPolicy::epsilon only. p and n must be finite.
template <class T>
Vec3<T> offset_origin(const Vec3<T>& p, const Vec3<T>& n, OffsetPolicy policy, T epsilon) {
    switch (policy) {
    case OffsetPolicy::none:
        return p;
    case OffsetPolicy::epsilon:
        return p + n * epsilon;
    case OffsetPolicy::ulp:
        break;
    }
    // Wächter & Binder's constants for float: 256 ULPs along n; below |p| = 1/32 a fixed 1/65536
    // along n. For double the fixed part shrinks with the machine epsilon.
    constexpr T int_scale = T(256);
    constexpr T origin_band = T(1) / T(32);
    constexpr T float_scale =
        T(1) / T(65536) *
        (std::numeric_limits<T>::epsilon() / T(std::numeric_limits<float>::epsilon()));
    Vec3<T> out;
    for (std::size_t i = 0; i < 3; ++i) {
        const auto ulps = static_cast<std::int64_t>(int_scale * n[i]);
        out[i] = std::abs(p[i]) < origin_band ? p[i] + float_scale * n[i]
                                              : detail::nudge_ulps(p[i], ulps);
    }
    return out;
}

}  // namespace rtlab
