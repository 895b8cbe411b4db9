#pragma once
// Catch2 helpers shared by the binary BVH tests: a registry row built with a leaf size and
// settings, and the tree's layout checked against its input boxes.

#include "accel/any_accel.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace rtlab::test {

/// The BVH of registry row `row` with max_leaf and any further settings (",key=value...").
inline Bvh build_with(const std::vector<Bounds3f>& boxes,
                      const std::string& row,
                      std::uint32_t max_leaf = 4,
                      const std::string& more = "") {
    const std::string spec = row + ",max_leaf=" + std::to_string(max_leaf) + more;
    return std::get<Bvh>(build_accel(spec, BuildInput{boxes, {}}));
}

/// Checks what validate() cannot see without the input: every usable box is referenced, every
/// leaf box is the union of its primitives' boxes (with `spatial`, of their parts: inside that
/// union), inner node boxes are the tight unions of their children's, and inner nodes' children
/// are adjacent and stored after them.
inline void check_layout(const Bvh& bvh, const std::vector<Bounds3f>& boxes, bool spatial = false) {
    REQUIRE(bvh.validate().empty());
    std::vector<char> referenced(boxes.size(), 0);
    for (const std::uint32_t id : bvh.prim_ids) {
        referenced[id] = 1;
    }
    std::uint32_t unusable = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Bounds3f& b = boxes[i];
        const bool usable = is_finite(b.lo) && is_finite(b.hi) && b.lo.x <= b.hi.x &&
                            b.lo.y <= b.hi.y && b.lo.z <= b.hi.z;
        CHECK(static_cast<bool>(referenced[i]) == usable);
        unusable += usable ? 0 : 1;
    }
    CHECK(bvh.unreferenced_count == unusable);
    for (std::size_t n = 0; n < bvh.nodes.size(); ++n) {
        const BvhNode& node = bvh.nodes[n];
        Bounds3f tight;
        if (node.is_leaf()) {
            for (std::uint32_t s = node.first; s < node.first + node.prim_count(); ++s) {
                tight.extend(boxes[bvh.prim_ids[s]]);
            }
            if (spatial) {
                CHECK(tight.contains(node.bounds()));
                continue;
            }
        } else {
            CHECK(node.first > n);
            CHECK(node.first % 2 == 1);  // pairs start after the root: 1, 3, 5, ...
            tight = merge(bvh.nodes[node.first].bounds(), bvh.nodes[node.first + 1].bounds());
        }
        CHECK(tight == node.bounds());
    }
}

}  // namespace rtlab::test
