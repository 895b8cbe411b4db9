#pragma once
// Adversarial ray sets for certified triangle hits (intersect/triangle/exact_hit.h, the exact
// query mode): random triangles with exact duplicates, far origins, integer lattices at several
// scales with rays aimed exactly at vertices and shared edges, axis-aligned rays, a perturbed
// closed sphere (also on a coarse grid), grazing and coplanar rays, origins on the surface.

#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtlab::test {

/// One ray set: a triangle list (ids are indices) and its rays.
struct RaySet {
    std::string name;
    std::vector<Trianglef> tris;
    std::vector<Rayf> rays;
};

/// Random triangles in [-1, 1]^3, a few repeated at the end (exact ties), and random rays with
/// random windows.
RaySet random_set(std::uint64_t seed);
/// Random triangles in [-1, 1]^3 seen from origins about 2^30 away, aimed exactly through the
/// centre (dir = -org): the vertices' offsets from the origin are not exact in double.
RaySet far_set(std::uint64_t seed);
/// Rays aimed exactly at the vertices and edge midpoints of a lattice terrain scaled by s (a power
/// of two), the target at t = 1, plus rays from random float origins passing near the targets.
RaySet lattice_set(std::uint64_t seed, float s);
/// Axis-aligned rays (one or two zero components, one denormal) at the lattice targets.
RaySet axis_set(float s);
/// The perturbed closed sphere: rays from the centre aimed exactly at every vertex, near edge
/// midpoints, and from random inner points.
RaySet sphere_set(std::uint64_t seed);
/// The perturbed sphere on the 2^-20 grid: rays aimed exactly at every vertex and edge midpoint.
RaySet quantized_sphere_set(std::uint64_t seed);
/// Integer triangles with rays lying exactly in a triangle's plane, and one ulp off it.
RaySet grazing_set(std::uint64_t seed);
/// Origins on the lattice surface (vertices, edge midpoints, inner points), windows from 0.
RaySet surface_set(std::uint64_t seed, float s);

/// Every set above with the seeds and scales (1, 2^-20, 2^20) the tests use.
std::vector<RaySet> exact_ray_sets();

}  // namespace rtlab::test
