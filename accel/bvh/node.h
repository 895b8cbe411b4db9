#pragma once
// The binary BVH node in Wald's 32-byte layout (Wald 2007; as in tinybvh's BVHNode): box minimum,
// one index word, box maximum, one packed count word. Children of an inner node are adjacent
// (left = first, right = first + 1), so one index addresses both.

#include "intersect/bounds.h"
#include "intersect/vec.h"

#include <cstdint>

namespace rtlab {

/// One BVH node. Packing of the second word: `(prim_count << 2) | axis`. prim_count == 0 marks an
/// inner node, whose `first` is the index of its left child and whose low two bits hold the split
/// axis (0, 1, 2) used to order traversal. prim_count > 0 marks a leaf, whose primitives are
/// prim_ids[first, first + prim_count); its axis bits are 0. A leaf holds at most 2^30 - 1
/// primitives.
struct alignas(32) BvhNode {
    Vec3f lo;                  ///< box minimum
    std::uint32_t first = 0;   ///< inner: left child index; leaf: first slot in prim_ids
    Vec3f hi;                  ///< box maximum
    std::uint32_t packed = 0;  ///< (prim_count << 2) | split axis

    /// Largest primitive count one leaf can hold.
    static constexpr std::uint32_t max_prim_count = (1u << 30) - 1;

    /// A leaf over prim_ids[first, first + count); count must be in [1, max_prim_count].
    static BvhNode make_leaf(const Bounds3f& box, std::uint32_t first_slot, std::uint32_t count) {
        return {box.lo, first_slot, box.hi, count << 2};
    }
    /// An inner node whose children are nodes[left] and nodes[left + 1], split on `axis`.
    static BvhNode make_inner(const Bounds3f& box, std::uint32_t left, std::uint32_t axis) {
        return {box.lo, left, box.hi, axis & 3u};
    }

    /// True for a leaf (non-zero primitive count).
    bool is_leaf() const { return (packed >> 2) != 0; }
    /// Number of primitives of a leaf (0 for an inner node).
    std::uint32_t prim_count() const { return packed >> 2; }
    /// Split axis of an inner node (0 for a leaf).
    std::uint32_t axis() const { return packed & 3u; }
    /// The node's box.
    Bounds3f bounds() const { return {lo, hi}; }

    friend bool operator==(const BvhNode&, const BvhNode&) = default;
};

static_assert(sizeof(BvhNode) == 32, "BvhNode must keep Wald's 32-byte layout");

}  // namespace rtlab
