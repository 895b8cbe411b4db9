#pragma once
// The float lanes of every SIMD level (base/simd_lanes.inc), each in its target region of
// base/simd.h: rtlab::simd_sse2, simd_avx2 and simd_avx512 hold L4, L8 (from AVX2 up), L16
// (AVX-512: the 16-wide node test only), max_lanes, max_node_lanes and LanesOf<W>. Kernels reopen
// these namespaces inside the same regions (see accel/bvh/wide_kernels.h) and pick a namespace per
// call by simd_level().

#include "base/simd.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <immintrin.h>

namespace rtlab {

/// The low bits of a lane_order_key<N> that hold the lane: 3 up to 8 slots, 4 for 16.
template <unsigned N>
inline constexpr std::int32_t lane_key_bits = N > 8 ? 15 : 7;

/// The order in which traversal visits the hit children of a node of N slots: by entry distance
/// t (the float's bits as a signed integer made monotone in t) with the lowest bits (3 up to 8
/// slots, 4 for 16) replaced by the lane, so keys are distinct, ties and distances within 8 (16)
/// ulps go in lane order, and a sorting network on the keys carries the lanes along (as Embree's
/// BVH8 traversal packs distance and slot).
template <unsigned N = 8>
inline std::int32_t lane_order_key(float t, unsigned lane) {
    static_assert(N <= 16);
    const auto b = std::bit_cast<std::int32_t>(t);
    const std::int32_t mono = b ^ ((b >> 31) & 0x7fffffff);
    return (mono & ~lane_key_bits<N>) | static_cast<std::int32_t>(lane);
}

/// The lanes set in mask (at least one; lanes below N) as lane_order_key<N>(t[lane], lane) in
/// ascending order in keys[0 .. count) by insertion; returns the count.
template <unsigned N = 8>
inline unsigned sort_lane_keys_scalar(const float* t, unsigned mask, std::int32_t* keys) {
    unsigned k = 0;
    do {
        const auto i = static_cast<unsigned>(__builtin_ctz(mask));
        mask &= mask - 1;
        const std::int32_t key = lane_order_key<N>(t[i], i);
        unsigned j = k++;
        for (; j > 0 && keys[j - 1] > key; --j) {
            keys[j] = keys[j - 1];
        }
        keys[j] = key;
    } while (mask != 0);
    return k;
}

}  // namespace rtlab

#define RTLAB_SIMD_KERNELS "base/simd_lanes.inc"
#include "base/simd_each_level.inc"
