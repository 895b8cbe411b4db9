#pragma once
// What the SoA leaf kernels (trace/triangle_soa.h, trace/sphere_soa.h) share: the groups of four
// slots their data is stored in, the hit a slot range reports and the lane masks of a slot range
// within a chunk of lanes.

#include "base/large_pages.h"
#include "intersect/hit.h"

#include <bit>
#include <cstddef>
#include <cstdint>

namespace rtlab {

/// Slots in groups of four, each group Rows rows of four floats (lane s % 4 of a row is slot s),
/// the last row the slots' ids as bits; one zero group of padding follows the last group, so
/// two-group (8-lane) loads from any slot's group stay inside the data.
template <std::uint32_t Rows>
struct SoaGroups {
    static constexpr std::uint32_t group = 4;                    ///< slots per group
    static constexpr std::uint32_t rows = Rows;                  ///< rows per group, ids included
    static constexpr std::uint32_t group_floats = group * rows;  ///< floats per group
    static constexpr unsigned id_row = Rows - 1;                 ///< the row of the ids
    std::uint32_t slots = 0;  ///< number of slots (without the padding)
    LargeVector<float> data;  ///< the groups, then one zero group

    /// Number of slots (without the padding).
    std::uint32_t size() const { return slots; }
    /// Bytes of the groups, padding included.
    std::size_t bytes() const { return data.size() * sizeof(float); }
    /// Row r of group g: four floats.
    const float* row(std::uint32_t g, unsigned r) const {
        return data.data() + std::size_t{g} * group_floats + std::size_t{r} * group;
    }
    /// Row r's float of slot s.
    float at(std::uint32_t s, unsigned r) const { return row(s / group, r)[s % group]; }
    /// The id stored for slot s.
    std::uint32_t id(std::uint32_t s) const {
        return std::bit_cast<std::uint32_t>(row(s / group, id_row)[s % group]);
    }
};

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
