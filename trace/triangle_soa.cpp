// TriangleSoA: building in slot order, and the leaf kernels of trace/triangle_soa_kernels.h for
// callers outside SIMD-level code, the level chosen per call.

#include "trace/triangle_soa.h"

#include "accel/accel.h"
#include "trace/triangle_soa_kernels.h"

#include <cassert>

namespace rtlab {

namespace {

/// The leaf kernel of the current SIMD level, for calls from outside the level's code.
template <bool IsWatertight>
std::optional<SlotHit> closest(const TriangleSoA& q,
                               std::uint32_t first,
                               std::uint32_t count,
                               Rayf& ray,
                               const WatertightRay<float>* wr) {
    switch (simd_level()) {
    case SimdLevel::avx512:
        return simd_avx512::soa_leaf_closest<IsWatertight>(q, first, count, ray, wr);
    case SimdLevel::avx2:
        return simd_avx2::soa_leaf_closest<IsWatertight>(q, first, count, ray, wr);
    case SimdLevel::sse2:
        break;
    }
    return simd_sse2::soa_leaf_closest<IsWatertight>(q, first, count, ray, wr);
}

template <bool IsWatertight>
std::optional<std::uint32_t> any(const TriangleSoA& q,
                                 std::uint32_t first,
                                 std::uint32_t count,
                                 const Rayf& ray,
                                 const WatertightRay<float>* wr) {
    switch (simd_level()) {
    case SimdLevel::avx512:
        return simd_avx512::soa_leaf_any<IsWatertight>(q, first, count, ray, wr);
    case SimdLevel::avx2:
        return simd_avx2::soa_leaf_any<IsWatertight>(q, first, count, ray, wr);
    case SimdLevel::sse2:
        break;
    }
    return simd_sse2::soa_leaf_any<IsWatertight>(q, first, count, ray, wr);
}

}  // namespace

VertexTriangleMethod<float>::Prepared TriangleSoA::vertices(std::uint32_t s) const {
    assert(layout == SoaLayout::vertices);
    return {{at(s, 0), at(s, 1), at(s, 2)},
            {at(s, 3), at(s, 4), at(s, 5)},
            {at(s, 6), at(s, 7), at(s, 8)}};
}

TriangleSoA make_triangle_soa(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                              std::span<const std::uint32_t> slot_ids,
                              SoaLayout layout,
                              std::span<const std::uint32_t> ids) {
    TriangleSoA q;
    q.layout = layout;
    q.slots = static_cast<std::uint32_t>(slot_ids.size());
    const std::size_t groups = (slot_ids.size() + TriangleSoA::group - 1) / TriangleSoA::group;
    q.data.assign((groups + 1) * TriangleSoA::group_floats, 0.0f);  // + the zero padding group
    for (std::size_t s = 0; s < slot_ids.size(); ++s) {
        if (slot_ids[s] == padding_slot) {
            continue;  // zeros: in no leaf, never tested
        }
        const auto& p = prims[slot_ids[s]];
        // The edges exactly as MollerTrumbore computes them.
        const Vec3f b = layout == SoaLayout::edges ? p.p1 - p.p0 : p.p1;
        const Vec3f c = layout == SoaLayout::edges ? p.p2 - p.p0 : p.p2;
        float* const g = q.data.data() + s / TriangleSoA::group * TriangleSoA::group_floats;
        const std::size_t lane = s % TriangleSoA::group;
        for (std::size_t k = 0; k < 3; ++k) {
            g[k * TriangleSoA::group + lane] = p.p0[k];
            g[(3 + k) * TriangleSoA::group + lane] = b[k];
            g[(6 + k) * TriangleSoA::group + lane] = c[k];
        }
        const std::uint32_t id = ids.empty() ? slot_ids[s] : ids[slot_ids[s]];
        g[9 * TriangleSoA::group + lane] = std::bit_cast<float>(id);
    }
    return q;
}

std::optional<SlotHit> soa_closest_mt(const TriangleSoA& soa,
                                      std::uint32_t first,
                                      std::uint32_t count,
                                      Rayf& ray) {
    return closest<false>(soa, first, count, ray, nullptr);
}

std::optional<std::uint32_t> soa_any_mt(const TriangleSoA& soa,
                                        std::uint32_t first,
                                        std::uint32_t count,
                                        const Rayf& ray) {
    return any<false>(soa, first, count, ray, nullptr);
}

std::optional<SlotHit> soa_closest_watertight(const TriangleSoA& soa,
                                              std::uint32_t first,
                                              std::uint32_t count,
                                              Rayf& ray,
                                              const WatertightRay<float>& wr) {
    return closest<true>(soa, first, count, ray, &wr);
}

std::optional<std::uint32_t> soa_any_watertight(const TriangleSoA& soa,
                                                std::uint32_t first,
                                                std::uint32_t count,
                                                const Rayf& ray,
                                                const WatertightRay<float>& wr) {
    return any<true>(soa, first, count, ray, &wr);
}

}  // namespace rtlab
