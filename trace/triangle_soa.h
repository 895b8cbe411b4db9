#pragma once
// Triangles structure-of-arrays in a structure's leaf-slot order, for testing a whole leaf at
// once: Möller–Trumbore and watertight (Woop et al. 2013) on 4 (SSE2) or 8 (AVX2, AVX-512) lanes
// (trace/triangle_soa_kernels.inc, the entries of trace/leaf_kernel.h's table). Each kernel gives
// exactly the answers of its scalar method applied to the slots one after another: lanes compute
// the same IEEE operations (no FMA), candidate lanes are then accepted in slot order against the
// shrinking window with the scalar comparisons, and watertight lanes with an exact zero edge
// function take the scalar method's double fallback.

#include "base/large_pages.h"
#include "intersect/hit.h"
#include "intersect/ray.h"
#include "intersect/triangle/moller_trumbore.h"
#include "intersect/triangle/watertight.h"
#include "trace/leaf_soa.h"

#include <bit>
#include <cstdint>
#include <span>

namespace rtlab {

/// What the nine coordinate rows of a TriangleSoA group hold.
enum class SoaLayout : std::uint8_t {
    edges,     ///< p0, e1 = p1 - p0, e2 = p2 - p0 (Möller–Trumbore)
    vertices,  ///< p0, p1, p2 (watertight)
};

/// Triangles by slot in groups of four: group g holds slots 4g .. 4g + 3 as nine rows of four
/// floats (a.x a.y a.z b.x b.y b.z c.x c.y c.z, see SoaLayout; lane s % 4 of a row is slot s) and
/// a row of their four ids (the caller's, e.g. global primitive ids), so a leaf's triangles and
/// the id of its hit lie in one or two adjacent 160-byte groups instead of in nine arrays and two
/// id maps (a dozen cache lines and pages per leaf; blocks of four triangles with their ids as
/// Embree's Triangle4 leaves).
/// One zero group of padding follows the last, so two-group (8-lane) loads from any slot's group
/// stay inside the data.
struct TriangleSoA : SoaGroups<10> {  // rows: 9 coordinates, id
    SoaLayout layout = SoaLayout::edges;
    /// The vertices of slot s as the scalar methods take them.
    VertexTriangleMethod<float>::Prepared vertices(std::uint32_t s) const;
};

/// The triangles prims[slot_ids[s]] for every slot s, in `layout`, each with the id
/// ids[slot_ids[s]] (slot_ids[s] itself when ids is empty); a padding_slot entry (accel/accel.h)
/// stays zero.
TriangleSoA make_triangle_soa(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                              std::span<const std::uint32_t> slot_ids,
                              SoaLayout layout,
                              std::span<const std::uint32_t> ids = {});

}  // namespace rtlab
