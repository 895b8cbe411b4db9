#pragma once
// Spheres structure-of-arrays in a structure's leaf-slot order, for testing a whole leaf at once
// with SphereStable<float> (intersect/sphere/stable.h) on 4 (SSE2) or 8 (AVX2, AVX-512) lanes
// (trace/sphere_soa_kernels.inc, an entry of trace/leaf_kernel.h's table). Each kernel gives
// exactly the answers of the scalar method applied to the slots one after another: lanes compute
// the roots with the same IEEE operations in the same order (no FMA), and candidate lanes are then
// accepted in slot order against the shrinking window with the comparisons of detail::pick_root. As
// the scalar method, the hits carry u = v = 0.

#include "base/large_pages.h"
#include "intersect/ray.h"
#include "intersect/sphere/stable.h"
#include "trace/leaf_soa.h"

#include <bit>
#include <cstdint>
#include <span>

namespace rtlab {

/// Spheres by slot in groups of four: group g holds slots 4g .. 4g + 3 as rows of four floats,
/// centre x, y, z, squared radius and the slot's id (the caller's, e.g. a global primitive id; lane
/// s % 4 of a row is slot s), so a leaf's spheres and the id of its hit lie in one or two adjacent
/// 80-byte groups. One zero group of padding follows the last, so two-group (8-lane) loads from
/// any slot's group stay inside the data.
struct SphereSoA : SoaGroups<5> {};  // rows: cx, cy, cz, radius2, id

/// The spheres prims[slot_ids[s]] for every slot s, each with the id ids[slot_ids[s]]
/// (slot_ids[s] itself when ids is empty); a padding_slot entry (accel/accel.h) stays zero.
SphereSoA make_sphere_soa(std::span<const PreparedSphere<float>> prims,
                          std::span<const std::uint32_t> slot_ids,
                          std::span<const std::uint32_t> ids = {});

}  // namespace rtlab
