#pragma once
// The wide BVH node test and traversal loop (accel/bvh/wide_traverse.inc) compiled once per SIMD
// level of base/simd.h: namespaces simd_sse2, simd_avx2 and simd_avx512, each in its own target
// region with that level's lanes (base/simd_lanes.h). WideBvh picks one per call by simd_level().

#include "accel/accel.h"
#include "accel/bvh/wide_node.h"
#include "base/prefetch.h"
#include "base/simd_lanes.h"
#include "intersect/box/slabs.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace rtlab {

/// What traversal reads of a WideBvh: its nodes (WideNode<N>, or QWideNode8 for a quantised
/// BVH8), leaf slots and, with `bounds=dop14`, the nodes' diagonal slabs.
template <class Node>
struct WideViewOf {
    const Node* nodes;
    const std::uint32_t* prim_ids;
    bool prefetch;  ///< prefetch hit children (nodes of at least prefetch_min_bytes)
    const WideDiag<Node::width>* diags;  ///< one per node, or null (boxes only)
};

/// A traversal stack entry: a child slot's reference and count (as in WideNode) and the entry
/// distance its box test gave.
struct WideEntry {
    std::uint32_t ref;
    std::uint32_t count;
    float t;
};

/// Stack entries traversal can need: at most N - 1 pushed per level, depth <= 64.
template <unsigned N>
inline constexpr unsigned wide_stack_size = 64 * (N - 1) + 1;

}  // namespace rtlab

#define RTLAB_SIMD_KERNELS "accel/bvh/wide_traverse.inc"
#include "base/simd_each_level.inc"
