#pragma once
// What the SoA leaf kernels (trace/triangle_soa.h, trace/sphere_soa.h) share: the hit a slot range
// reports and the lane masks of a slot range within a chunk of lanes.

#include "intersect/hit.h"

#include <cstdint>

namespace rtlab {

/// The accepted hit of a slot range: its slot and hit.
struct SlotHit {
    std::uint32_t slot;
    PrimHit<float> hit;
};

/// Bits of the lanes below n (n may exceed the lane count).
inline unsigned soa_first_lanes(std::uint32_t n) {
    return n >= 32 ? ~0u : (1u << n) - 1u;
}

/// Bits of the lanes of a chunk starting at slot s0 whose slots lie in [first, end).
inline unsigned soa_lanes_in(std::uint32_t s0, std::uint32_t first, std::uint32_t end) {
    return soa_first_lanes(end - s0) & ~soa_first_lanes(first > s0 ? first - s0 : 0);
}

}  // namespace rtlab
