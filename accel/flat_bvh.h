#pragma once
// A BVH layout flattened into one node list, the form in which the cost model and the end-point
// overlap (accel/cost_model.h) read every BVH. A layout joins them by offering
// `FlatBvh flatten(const Layout&)` beside its type (found by argument-dependent lookup); a
// structure without one gives its own `expected_cost` overload instead.

#include "intersect/bounds.h"

#include <cstdint>
#include <span>
#include <vector>

namespace rtlab {

/// One node of a flattened BVH: its box and either children (kids[kid_first, kid_end)) or leaf
/// slots prim_ids[first, first + count).
struct FlatNode {
    Bounds3f box;
    std::uint32_t kid_first = 0, kid_end = 0;
    std::uint32_t first = 0, count = 0;
    bool leaf() const { return count > 0; }
};

/// The nodes of a BVH, root at 0, as traversal meets them.
struct FlatBvh {
    std::vector<FlatNode> nodes;  ///< root at 0
    std::vector<std::uint32_t> kids;
    std::span<const std::uint32_t> prim_ids;
    bool counts_child_tests = true;  ///< binary layouts count every child box test as a node

    /// Appends a node and returns its index.
    std::uint32_t add(const Bounds3f& box, std::uint32_t first, std::uint32_t count) {
        nodes.push_back({box, 0, 0, first, count});
        return static_cast<std::uint32_t>(nodes.size() - 1);
    }
};

}  // namespace rtlab
