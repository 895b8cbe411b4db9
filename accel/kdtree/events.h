#pragma once
// Split-candidate events of the kd-tree SAH sweep (Wald & Havran 2006, section 4.2), packed in
// one 64-bit word so that sorting the integers sorts the events: the position's order-preserving
// bits (32), the type (2: end < planar < start at equal positions) and the primitive id (30, the
// kd-tree's own limit). Sorting: an LSD radix sort on the position and type bits (the lists are
// generated in id order and the sort is stable, so ties stay in id order), std::sort when short.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace rtlab::kd_detail {

/// One boundary of a primitive's clipped box along one axis.
using Event = std::uint64_t;

/// Event kinds, in the order they sort at equal positions.
enum EventType : std::uint32_t { event_end = 0, event_planar = 1, event_start = 2 };

/// The float's bits mapped so that unsigned order is float order (-0 and +0 map alike).
inline std::uint32_t order_bits(float f) {
    const auto u = std::bit_cast<std::uint32_t>(f + 0.0f);
    return (u & 0x80000000u) != 0 ? ~u : (u | 0x80000000u);
}

/// Inverse of order_bits.
inline float from_order_bits(std::uint32_t u) {
    return std::bit_cast<float>((u & 0x80000000u) != 0 ? (u & 0x7FFFFFFFu) : ~u);
}

inline Event make_event(float pos, EventType type, std::uint32_t prim) {
    return (static_cast<std::uint64_t>(order_bits(pos)) << 32) |
           (static_cast<std::uint64_t>(type) << 30) | prim;
}

inline std::uint32_t event_prim(Event e) {
    return static_cast<std::uint32_t>(e & 0x3FFFFFFFu);
}
inline EventType event_type(Event e) {
    return static_cast<EventType>((e >> 30) & 3u);
}
/// The position's order bits (equal positions have equal bits).
inline std::uint32_t event_pos_bits(Event e) {
    return static_cast<std::uint32_t>(e >> 32);
}
inline float event_pos(Event e) {
    return from_order_bits(event_pos_bits(e));
}

/// Sorts events whose equal (position, type) keys are already in id order.
inline void sort_events(std::vector<Event>& v) {
    constexpr std::size_t radix_min = 2048;
    if (v.size() < radix_min) {
        std::sort(v.begin(), v.end());
        return;
    }
    // Bits 30..63 (position and type): three stable 12-bit passes.
    constexpr int digit_bits = 12;
    constexpr std::size_t buckets = std::size_t{1} << digit_bits;
    std::vector<Event> tmp(v.size());
    std::vector<std::uint32_t> count(buckets);
    for (int shift = 30; shift < 64; shift += digit_bits) {
        std::fill(count.begin(), count.end(), 0u);
        for (const Event e : v) {
            ++count[(e >> shift) & (buckets - 1)];
        }
        std::uint32_t sum = 0;
        for (std::uint32_t& c : count) {
            const std::uint32_t n = c;
            c = sum;
            sum += n;
        }
        for (const Event e : v) {
            tmp[count[(e >> shift) & (buckets - 1)]++] = e;
        }
        v.swap(tmp);
    }
}

/// The three axes' sorted event lists of one node.
using EventLists = std::array<std::vector<Event>, 3>;

}  // namespace rtlab::kd_detail
