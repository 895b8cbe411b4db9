#pragma once
// The 8-byte kd-tree node (the layout of pbrt's KdTreeNode, Pharr et al., "Physically Based
// Rendering", 3rd ed., 4.4): one 32-bit payload (the split position's bits, or the offset of the
// leaf's primitive list) and one 32-bit word holding 2 axis bits (3 = leaf) and 30 bits of either
// the above-child index (inner; the below child is the next node) or the primitive count (leaf).

#include <bit>
#include <cstdint>

namespace rtlab {

/// A kd-tree node: inner (axis, split, above child) or leaf (offset and count into prim_ids).
struct KdNode {
    std::uint32_t payload = 0;  ///< inner: bit pattern of the split float; leaf: list offset
    std::uint32_t bits = 3;     ///< low 2 bits: axis 0..2, or 3 for a leaf; high 30: see above

    /// Largest above-child index or primitive count the node can hold (2^30 - 1).
    static constexpr std::uint32_t max_index = (1u << 30) - 1;

    /// An inner node splitting `axis` at `split`; `above` is the index of the child with
    /// coordinates >= split (the child below the split is the node right after this one).
    static constexpr KdNode inner(std::uint32_t axis, float split, std::uint32_t above) {
        return {std::bit_cast<std::uint32_t>(split), (above << 2) | axis};
    }
    /// A leaf holding prim_ids[offset, offset + count).
    static constexpr KdNode leaf(std::uint32_t offset, std::uint32_t count) {
        return {offset, (count << 2) | 3u};
    }

    /// True for a leaf.
    constexpr bool is_leaf() const { return (bits & 3u) == 3u; }
    /// Split axis 0..2 (inner nodes only).
    constexpr std::uint32_t axis() const { return bits & 3u; }
    /// Split position (inner nodes only).
    constexpr float split() const { return std::bit_cast<float>(payload); }
    /// Index of the child above the split (inner nodes only).
    constexpr std::uint32_t above_child() const { return bits >> 2; }
    /// First entry of the leaf's primitive list in prim_ids (leaves only).
    constexpr std::uint32_t prim_offset() const { return payload; }
    /// Number of primitives in the leaf (leaves only).
    constexpr std::uint32_t prim_count() const { return bits >> 2; }

    friend constexpr bool operator==(const KdNode&, const KdNode&) = default;
};

static_assert(sizeof(KdNode) == 8, "the kd node is 8 bytes");

}  // namespace rtlab
