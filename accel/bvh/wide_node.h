#pragma once
// The node of the wide BVHs (BVH4, BVH8): N child boxes stored structure-of-arrays (one row of N
// floats per box plane), so one SIMD slab test clips the ray against every child at once (Wald,
// Benthin & Boulos 2008, "Getting rid of packets"; as Embree's BVH4/8 and tinybvh's BVH8_CPU).

#include "intersect/bounds.h"

#include <cstdint>

namespace rtlab {

/// One wide node of N child slots. Slot i is empty (child[i] == empty_slot, box lo = +inf,
/// hi = -inf so every slab test misses it), an inner child (count[i] == 0, child[i] = its node
/// index) or a leaf (count[i] > 0 primitives from slot child[i] of prim_ids). Occupied slots come
/// first.
template <unsigned N>
struct alignas(64) WideNode {
    static_assert(N == 4 || N == 8, "wide nodes hold 4 or 8 children");
    static constexpr std::uint32_t empty_slot = 0xffffffffu;

    float lo[3][N];          ///< lo[axis][slot]: child box minima
    float hi[3][N];          ///< hi[axis][slot]: child box maxima
    std::uint32_t child[N];  ///< inner: node index; leaf: first prim_ids slot; empty_slot
    std::uint32_t count[N];  ///< leaf primitive count; 0 for inner and empty slots

    /// A node with every slot empty.
    static WideNode empty() {
        WideNode n{};
        for (unsigned i = 0; i < N; ++i) {
            n.set(i, Bounds3f{}, empty_slot, 0);  // Bounds3f{}: lo = +inf, hi = -inf
        }
        return n;
    }

    /// Stores slot i: its box, child index (or first slot) and leaf count.
    void set(unsigned i, const Bounds3f& box, std::uint32_t c, std::uint32_t n) {
        for (unsigned a = 0; a < 3; ++a) {
            lo[a][i] = box.lo[a];
            hi[a][i] = box.hi[a];
        }
        child[i] = c;
        count[i] = n;
    }

    /// The box of slot i.
    Bounds3f bounds(unsigned i) const {
        return {{lo[0][i], lo[1][i], lo[2][i]}, {hi[0][i], hi[1][i], hi[2][i]}};
    }
    /// True when slot i holds a child.
    bool occupied(unsigned i) const { return child[i] != empty_slot; }
    /// True when slot i holds a leaf.
    bool is_leaf(unsigned i) const { return occupied(i) && count[i] != 0; }

    friend bool operator==(const WideNode&, const WideNode&) = default;
};

static_assert(sizeof(WideNode<4>) == 128 && sizeof(WideNode<8>) == 256);

}  // namespace rtlab
