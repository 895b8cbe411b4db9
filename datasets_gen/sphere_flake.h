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

/// Unit offset of child k (0..8) in its parent's frame (+Z = parent axis): six on the equator at
/// azimuths 15 + 60j degrees, three at elevation asin(sqrt(2/3)) at azimuths 45 + 120j degrees.
[[nodiscard]] Vec3d flake_child_offset(int k);

/// Orthonormal frame (u, v, axis) around a unit axis, chosen deterministically: u = normalize(Y x
/// axis) unless |axis.y| > 0.9, then u = normalize(Z x axis); v = axis x u. For the root (+Z) this
/// is u = +X, v = +Y, so azimuths are measured from +X towards +Y.
void flake_frame(const Vec3d& axis, Vec3d& u, Vec3d& v);

/// All spheres of a flake of size factor sf (0 = the root only), root first, breadth-first order;
/// root centre (0,0,0), radius 0.5, axis +Z. Does not check memory: callers guard the size.
[[nodiscard]] std::vector<FlakeSphere> sphere_flake(int sf);

}  // namespace rtlab::gen
