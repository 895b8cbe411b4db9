#pragma once
// The node of the wide BVHs (BVH4, BVH8, BVH16): N child boxes stored structure-of-arrays (one row
// of N floats per box plane), so one SIMD slab test clips the ray against every child at once
// (Wald, Benthin & Boulos 2008, "Getting rid of packets"; as Embree's BVH4/8 and tinybvh's
// BVH8_CPU).

#include "accel/bvh/diag_slabs.h"
#include "intersect/bounds.h"

#include <cstddef>
#include <cstdint>

namespace rtlab {

/// One wide node of N child slots. Slot i is empty (child[i] == empty_slot, box lo = +inf,
/// hi = -inf so every slab test misses it), an inner child (count[i] == 0, child[i] = its node
/// index) or a leaf (count[i] > 0 primitives from slot child[i] of prim_ids). Occupied slots come
/// first.
template <unsigned N>
struct alignas(64) WideNode {
    static_assert(N == 4 || N == 8 || N == 16, "wide nodes hold 4, 8 or 16 children");
    static constexpr unsigned width = N;
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

    /// Byte offset of the row of N planes on `axis`: minima (side 0) or maxima (side 1).
    static constexpr std::size_t plane_row(unsigned side, unsigned axis) {
        return (side == 0 ? offsetof(WideNode, lo) : offsetof(WideNode, hi)) + axis * sizeof(lo[0]);
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

static_assert(sizeof(WideNode<4>) == 128 && sizeof(WideNode<8>) == 256 &&
              sizeof(WideNode<16>) == 512);

/// The diagonal slabs of a WideNode<N>'s slots (`bounds=dop14`; the node's boxes and these make
/// each slot a 14-DOP): lo[k][i] and hi[k][i] bound dot(diag_dirs[k], x) over slot i's
/// primitives; an empty slot holds lo = +inf, hi = -inf. Kept in an array beside the nodes, one
/// per node, so the box-only traversal reads the same nodes as without them.
template <unsigned N>
struct alignas(64) WideDiag {
    float lo[4][N];
    float hi[4][N];

    /// Byte offset of the row of N planes in direction k: minima (side 0) or maxima (side 1).
    static constexpr std::size_t plane_row(unsigned side, unsigned k) {
        return (side == 0 ? offsetof(WideDiag, lo) : offsetof(WideDiag, hi)) + k * sizeof(lo[0]);
    }

    friend bool operator==(const WideDiag&, const WideDiag&) = default;
};

/// A WideNode<8> with its child boxes quantised to one byte per plane on a per-node grid (Ylitie,
/// Karras & Laine 2017, "Efficient incoherent ray traversal on GPUs through compressed wide BVHs";
/// Embree's compressed BVH8 nodes): 128 bytes, two cache lines where WideNode<8> takes four. Plane
/// k of an axis lies at origin + k * scale (float operations, rounded as written), and every slot's
/// planes enclose its WideNode box (quantize_wide_node rounds outward and checks each value), so a
/// slab test of the dequantised box misses only what the exact box misses.
struct alignas(64) QWideNode8 {
    static constexpr unsigned width = 8;

    float origin[3];          ///< the grid's origin (the node's box minimum)
    float scale[3];           ///< the grid's step per axis (>= 0)
    std::uint8_t q[2][3][8];  ///< q[side][axis][slot]: plane codes, minima then maxima
    std::uint32_t child[8];   ///< as WideNode<8>::child
    std::uint16_t count[8];   ///< as WideNode<8>::count
    std::uint8_t occupied;    ///< bit i set when slot i holds a child
    std::uint8_t pad[7];

    /// The plane of code k on `axis`, exactly as traversal's lanes compute it.
    float plane(unsigned axis, std::uint8_t k) const {
        return origin[axis] + static_cast<float>(k) * scale[axis];
    }
    /// The dequantised box of slot i (encloses the WideNode box it was made from).
    Bounds3f bounds(unsigned i) const {
        return {{plane(0, q[0][0][i]), plane(1, q[0][1][i]), plane(2, q[0][2][i])},
                {plane(0, q[1][0][i]), plane(1, q[1][1][i]), plane(2, q[1][2][i])}};
    }
    /// Byte offset of the row of 8 plane codes on `axis`, minima (side 0) or maxima (side 1).
    static constexpr std::size_t plane_row(unsigned side, unsigned axis) {
        return offsetof(QWideNode8, q) + (side * 3 + axis) * 8;
    }

    friend bool operator==(const QWideNode8&, const QWideNode8&) = default;
};

static_assert(sizeof(QWideNode8) == 128);

/// n quantised: the tightest codes whose planes enclose each occupied slot's box on a grid from
/// the node's box minimum with 255 steps reaching its maximum; throws std::invalid_argument for a
/// leaf of more than 65535 primitives (the count field's range).
QWideNode8 quantize_wide_node(const WideNode<8>& n);

}  // namespace rtlab
