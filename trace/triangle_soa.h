#pragma once
// Triangles structure-of-arrays in a structure's leaf-slot order, for testing a whole leaf at
// once: Möller–Trumbore and watertight (Woop et al. 2013) on 4 (SSE2) or 8 (AVX2, AVX-512) lanes,
// the level chosen per call by base/simd.h. Each kernel gives exactly the answers of its scalar
// method applied to the slots one after another: lanes compute the same IEEE operations (no FMA),
// candidate lanes are then accepted in slot order against the shrinking window with the scalar
// comparisons, and watertight lanes with an exact zero edge function take the scalar method's
// double fallback.

#include "intersect/hit.h"
#include "intersect/ray.h"
#include "intersect/triangle/moller_trumbore.h"
#include "intersect/triangle/watertight.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace rtlab {

/// What the nine arrays of a TriangleSoA hold.
enum class SoaLayout : std::uint8_t {
    edges,     ///< p0, e1 = p1 - p0, e2 = p2 - p0 (Möller–Trumbore)
    vertices,  ///< p0, p1, p2 (watertight)
};

/// Triangles by slot: a[axis][slot], b[axis][slot], c[axis][slot] (see SoaLayout), padded with
/// zero triangles so that 8-lane loads from any slot stay inside the arrays.
struct TriangleSoA {
    static constexpr std::uint32_t pad = 8;
    SoaLayout layout = SoaLayout::edges;
    std::vector<float> a[3], b[3], c[3];

    /// Number of slots (without the padding).
    std::uint32_t size() const {
        return a[0].empty() ? 0 : static_cast<std::uint32_t>(a[0].size() - pad);
    }
    /// The vertices of slot s as the scalar methods take them.
    VertexTriangleMethod<float>::Prepared vertices(std::uint32_t s) const;
};

/// The triangles prims[slot_ids[s]] for every slot s, in `layout`.
TriangleSoA make_triangle_soa(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                              std::span<const std::uint32_t> slot_ids,
                              SoaLayout layout);

/// The accepted hit of a slot range: its slot and hit.
struct SlotHit {
    std::uint32_t slot;
    PrimHit<float> hit;
};

/// Closest hit among slots [first, first + count), exactly as MollerTrumbore<float>::intersect
/// on each slot in order, each hit shrinking ray.tmax (which this does too); nullopt if none.
/// soa.layout must be edges.
std::optional<SlotHit> soa_closest_mt(const TriangleSoA& soa,
                                      std::uint32_t first,
                                      std::uint32_t count,
                                      Rayf& ray);

/// The first slot of [first, first + count) MollerTrumbore<float>::occluded reports, or nullopt.
std::optional<std::uint32_t> soa_any_mt(const TriangleSoA& soa,
                                        std::uint32_t first,
                                        std::uint32_t count,
                                        const Rayf& ray);

/// As soa_closest_mt for Watertight<float> with the ray's set-up wr; layout must be vertices.
std::optional<SlotHit> soa_closest_watertight(const TriangleSoA& soa,
                                              std::uint32_t first,
                                              std::uint32_t count,
                                              Rayf& ray,
                                              const WatertightRay<float>& wr);

/// As soa_any_mt for Watertight<float>.
std::optional<std::uint32_t> soa_any_watertight(const TriangleSoA& soa,
                                                std::uint32_t first,
                                                std::uint32_t count,
                                                const Rayf& ray,
                                                const WatertightRay<float>& wr);

}  // namespace rtlab
