#pragma once
// The axis-aligned planes a built structure decides on, read from the structure itself: a
// kd-tree's split planes within their cells, a grid's cell boundaries (both levels of the
// two-level grid), a BVH layout's node box faces. The adversarial ray sets aim at them.

#include "accel/any_accel.h"
#include "intersect/bounds.h"

#include <cstdint>
#include <vector>

namespace rtlab::stab {

/// One plane x[axis] == pos and the face of it where the structure's decision happens (a split
/// within its node's cell, a cell boundary across its grid, a box face); face.lo[axis] ==
/// face.hi[axis] == pos.
struct StructurePlane {
    std::uint32_t axis = 0;
    float pos = 0;
    Bounds3f face;
};

/// Every plane of the structure `a` holds (brute force: its scene box's faces).
std::vector<StructurePlane> structure_planes(const AnyAccel& a);

}  // namespace rtlab::stab
