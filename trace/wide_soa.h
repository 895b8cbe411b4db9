#pragma once
// Wide BVHs over TriangleSoA or SphereSoA leaf data with the leaf kernel inlined into traversal:
// one function per SIMD level (trace/wide_soa.inc) holds the node tests and the leaf tests of that
// level, so a leaf costs no call and no level look-up. The answers are those of
// WideBvh::intersect_leaves / occluded_leaves with soa_closest_* / soa_any_* (sphere_soa_closest /
// sphere_soa_any) as the leaf callback (same order of visits, same counts).

#include "accel/bvh/wide_bvh.h"
#include "trace/sphere_soa_kernels.h"
#include "trace/triangle_soa_kernels.h"

#include <cstdint>
#include <optional>
#include <type_traits>

namespace rtlab {

/// What a wide_soa_trace query finds: the closest hit's slot and hit, or any hit's slot.
template <bool IsAnyHit>
using SoaFound = std::conditional_t<IsAnyHit, std::optional<std::uint32_t>, std::optional<SlotHit>>;

}  // namespace rtlab

namespace rtlab::simd_sse2 {
#include "trace/wide_soa.inc"
}  // namespace rtlab::simd_sse2

RTLAB_SIMD_BEGIN_AVX2
namespace rtlab::simd_avx2 {
#include "trace/wide_soa.inc"
}  // namespace rtlab::simd_avx2
RTLAB_SIMD_END

RTLAB_SIMD_BEGIN_AVX512
namespace rtlab::simd_avx512 {
#include "trace/wide_soa.inc"
}  // namespace rtlab::simd_avx512
RTLAB_SIMD_END

namespace rtlab {

/// True for WideBvh<N>.
template <class A>
inline constexpr bool is_wide_bvh = false;
template <unsigned N>
inline constexpr bool is_wide_bvh<WideBvh<N>> = true;

/// Closest hit (IsAnyHit false, R is Rayf: the nearest slot and its hit, ray.tmax shrunk to it)
/// or any hit (R is const Rayf: the first blocking slot found) through bvh with leaf data q in its
/// slot order: Möller–Trumbore for the edges layout, watertight with the ray's set-up *wr for the
/// vertices layout.
template <bool IsAnyHit, bool IsRobust, bool IsWatertight, unsigned N, class R, StatsSink S>
SoaFound<IsAnyHit> wide_soa_trace(
    const WideBvh<N>& bvh, const TriangleSoA& q, R& ray, const WatertightRay<float>* wr, S& stats) {
    return bvh.visit(ray, stats, SoaFound<IsAnyHit>{}, [&](const auto& view) {
        switch (simd_level()) {
        case SimdLevel::avx512:
            return simd_avx512::wide_soa_trace<IsAnyHit, IsRobust, IsWatertight>(view, q, ray, wr,
                                                                                 stats);
        case SimdLevel::avx2:
            return simd_avx2::wide_soa_trace<IsAnyHit, IsRobust, IsWatertight>(view, q, ray, wr,
                                                                               stats);
        case SimdLevel::sse2:
            break;
        }
        return simd_sse2::wide_soa_trace<IsAnyHit, IsRobust, IsWatertight>(view, q, ray, wr, stats);
    });
}

/// As wide_soa_trace for spheres: SphereStable<float> with the ray's set-up rd on leaf data q in
/// bvh's slot order.
template <bool IsAnyHit, bool IsRobust, unsigned N, class R, StatsSink S>
SoaFound<IsAnyHit> wide_sphere_trace(
    const WideBvh<N>& bvh, const SphereSoA& q, R& ray, const SphereRay<float>& rd, S& stats) {
    return bvh.visit(ray, stats, SoaFound<IsAnyHit>{}, [&](const auto& view) {
        switch (simd_level()) {
        case SimdLevel::avx512:
            return simd_avx512::wide_sphere_trace<IsAnyHit, IsRobust>(view, q, ray, rd, stats);
        case SimdLevel::avx2:
            return simd_avx2::wide_sphere_trace<IsAnyHit, IsRobust>(view, q, ray, rd, stats);
        case SimdLevel::sse2:
            break;
        }
        return simd_sse2::wide_sphere_trace<IsAnyHit, IsRobust>(view, q, ray, rd, stats);
    });
}

}  // namespace rtlab
