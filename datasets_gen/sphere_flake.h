#pragma once
// Sphere flake of Eric Haines' Standard Procedural Databases ("balls", SPD 1987): a root sphere
// with nine tangent children of a third of its radius each, recursively. Spheres = (9^(SF+1) - 1)
// / 8.

#include "intersect/vec.h"

#include <cstdint>
#include <vector>

namespace rtlab::gen {

/// One sphere of the flake, in double precision (callers narrow to float when they store it).
struct FlakeSphere {
    Vec3d center;              ///< centre in world space
    double radius = 0;         ///< radius (> 0)
    Vec3d axis{0, 0, 1};       ///< unit axis: direction from the parent's centre to this one
    std::uint32_t parent = 0;  ///< index of the parent sphere (the root is its own parent)
    std::uint32_t depth = 0;   ///< 0 for the root, k for the k-th generation
};

/// Number of spheres of a flake of size factor sf: (9^(sf+1) - 1) / 8 (sf 4 -> 7381).
[[nodiscard]] std::uint64_t flake_sphere_count(int sf);

/// Unit offset of child k (0..8) in its parent's frame (+Z = parent axis), in balls.c's order: a
/// trio (1,1,0)/sqrt2, (1,0,-1)/sqrt2, (0,1,-1)/sqrt2 turned about (1,-1,0)/sqrt2 by
/// asin(2/sqrt6), then the trio turned about Z by 0, 120 and 240 degrees. Three children lie at
/// elevation asin(sqrt(2/3)) (azimuths 45, 165, 285) and six on the equator.
[[nodiscard]] Vec3d flake_child_offset(int k);

/// The SPD's rotation of the offset set onto a child direction d (balls.c): the minimal rotation
/// taking +Z onto d (axis Z x d, angle acos(d.z)); identity for d.z >= 0.9999 and a half turn
/// about Y for d.z <= -0.9999. Returns where it takes the offset o.
[[nodiscard]] Vec3d flake_rotate(const Vec3d& d, const Vec3d& o);

/// All spheres of a flake of size factor sf (0 = the root only), root first, breadth-first order
/// (balls.c writes them depth-first); root centre (0,0,0), radius 0.5, axis +Z. Does not check
/// memory: callers guard the size.
[[nodiscard]] std::vector<FlakeSphere> sphere_flake(int sf);

}  // namespace rtlab::gen
