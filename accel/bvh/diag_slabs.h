#pragma once
// The diagonal slabs of the wide BVHs' `bounds=dop14` (accel/bvh/wide_diag.cpp): four directions
// beside the box's three axes, and a primitive's extents along them.

#include "accel/accel.h"
#include "intersect/bounds.h"

namespace rtlab {

/// The diagonal directions of the extra slabs: (1, 1, 1), (1, 1, -1), (1, -1, 1) and (-1, 1, 1),
/// unnormalised (with the box's three axes, the 14-DOP's seven slab directions; Kay & Kajiya
/// 1986, Klosowski et al. 1998).
inline constexpr float diag_dirs[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};

/// diag_dirs[k] as a vector.
inline Vec3f diag_dir(unsigned k) {
    return {diag_dirs[k][0], diag_dirs[k][1], diag_dirs[k][2]};
}

/// dot(diag_dirs[k], p) in double: each term exact (+-p's component), the two sums rounded (error
/// below 2 * 2^-53 times |p.x| + |p.y| + |p.z|).
inline double diag_dot(unsigned k, const Vec3f& p) {
    return extent_dot(diag_dir(k), p);
}

/// The corner of box b lowest along diag_dirs[k] (`low`) or highest.
inline Vec3f diag_corner(const Bounds3f& b, unsigned k, bool low) {
    const auto pick = [&](unsigned a) { return (diag_dirs[k][a] > 0) == low ? b.lo[a] : b.hi[a]; };
    return {pick(0), pick(1), pick(2)};
}

/// A primitive's extents along diag_dirs: every point x of it has lo[k] <= dot(diag_dirs[k], x)
/// <= hi[k] (exactly: the values are rounded outward).
struct DiagExtents {
    float lo[4];
    float hi[4];
};

/// DiagExtents of a box (its corners'), rounded outward.
DiagExtents diag_extents_of_box(const Bounds3f& b);

/// DiagExtents of primitive `id` from the build input's ExtentFn (`in.extent`, which must be set).
DiagExtents diag_extents_of(const BuildInput& in, std::uint32_t id);

}  // namespace rtlab
