// TriangleSoA: building in slot order, and the leaf kernels: per-level lane chunks
// (trace/triangle_soa_kernels.inc), then the scalar acceptance of candidate lanes in slot order.

#include "trace/triangle_soa.h"

#include "base/simd_lanes.h"

#include <cassert>

namespace rtlab {

namespace {

/// One chunk of at most 8 slots: `cand` has a bit per lane that may hit (it passed every test
/// against the window the chunk started with, which only shrinks); `fallback` marks watertight
/// lanes with an exact zero edge function, which the scalar method decides. Per lane: t, u, v,
/// and for watertight the scaled distance ts and |det| of its window test.
struct SoaChunk {
    unsigned cand = 0;
    unsigned fallback = 0;
    alignas(32) float t[8];
    alignas(32) float u[8];
    alignas(32) float v[8];
    alignas(32) float ts[8];
    alignas(32) float ad[8];
};

}  // namespace

namespace simd_sse2 {
#include "trace/triangle_soa_kernels.inc"
}  // namespace simd_sse2

RTLAB_SIMD_BEGIN_AVX2
namespace simd_avx2 {
#include "trace/triangle_soa_kernels.inc"
}  // namespace simd_avx2
RTLAB_SIMD_END

RTLAB_SIMD_BEGIN_AVX512
namespace simd_avx512 {
#include "trace/triangle_soa_kernels.inc"
}  // namespace simd_avx512
RTLAB_SIMD_END

namespace {

unsigned lanes_of(SimdLevel l) {
    return l == SimdLevel::sse2 ? simd_sse2::max_lanes : simd_avx2::max_lanes;
}

/// Bits of the lanes below n (n may exceed the lane count).
unsigned first_lanes(std::uint32_t n) {
    return n >= 32 ? ~0u : (1u << n) - 1u;
}

/// Bits of the lanes of a chunk starting at slot s0 whose slots lie in [first, end).
unsigned lanes_in(std::uint32_t s0, std::uint32_t first, std::uint32_t end) {
    return first_lanes(end - s0) & ~first_lanes(first > s0 ? first - s0 : 0);
}

void chunk_mt(SimdLevel l, const TriangleSoA& q, std::uint32_t g, const Rayf& ray, SoaChunk& c) {
    switch (l) {
    case SimdLevel::avx512:
        return simd_avx512::soa_chunk_mt(q, g, ray, c);
    case SimdLevel::avx2:
        return simd_avx2::soa_chunk_mt(q, g, ray, c);
    case SimdLevel::sse2:
        break;
    }
    simd_sse2::soa_chunk_mt(q, g, ray, c);
}

void chunk_watertight(SimdLevel l,
                      const TriangleSoA& q,
                      std::uint32_t g,
                      const Rayf& ray,
                      const WatertightRay<float>& wr,
                      SoaChunk& c) {
    switch (l) {
    case SimdLevel::avx512:
        return simd_avx512::soa_chunk_watertight(q, g, ray, wr, c);
    case SimdLevel::avx2:
        return simd_avx2::soa_chunk_watertight(q, g, ray, wr, c);
    case SimdLevel::sse2:
        break;
    }
    simd_sse2::soa_chunk_watertight(q, g, ray, wr, c);
}

/// The scalar method's verdict for candidate lane i of chunk c (slot s + i) with the current
/// window: MT accepts t inside the window; watertight redoes its scaled window test first, or
/// runs the whole scalar method for fallback lanes.
template <bool IsWatertight>
std::optional<PrimHit<float>> accept(const TriangleSoA& q,
                                     const SoaChunk& c,
                                     unsigned i,
                                     std::uint32_t slot,
                                     const Rayf& ray,
                                     const WatertightRay<float>* wr) {
    if constexpr (IsWatertight) {
        if ((c.fallback >> i) & 1u) {
            return Watertight<float>::intersect(q.vertices(slot), ray, *wr);
        }
        if (!(c.ts[i] >= ray.tmin * c.ad[i] && c.ts[i] <= ray.tmax * c.ad[i])) {
            return std::nullopt;
        }
    }
    if (!in_window(c.t[i], ray)) {
        return std::nullopt;
    }
    return PrimHit<float>{c.t[i], c.u[i], c.v[i]};
}

template <bool IsWatertight>
std::optional<SlotHit> closest(const TriangleSoA& q,
                               std::uint32_t first,
                               std::uint32_t count,
                               Rayf& ray,
                               const WatertightRay<float>* wr) {
    const SimdLevel l = simd_level();
    const unsigned w = lanes_of(l);
    const std::uint32_t end = first + count;
    std::optional<SlotHit> best;
    SoaChunk c;
    // Chunks of w lanes from the group holding `first`; lanes outside the range are ignored.
    for (std::uint32_t s = first / TriangleSoA::group * TriangleSoA::group; s < end; s += w) {
        if constexpr (IsWatertight) {
            chunk_watertight(l, q, s / TriangleSoA::group, ray, *wr, c);
        } else {
            chunk_mt(l, q, s / TriangleSoA::group, ray, c);
        }
        for (unsigned m = c.cand & lanes_in(s, first, end); m != 0; m &= m - 1) {
            const auto i = static_cast<unsigned>(__builtin_ctz(m));
            if (const auto h = accept<IsWatertight>(q, c, i, s + i, ray, wr)) {
                ray.tmax = h->t;
                best = SlotHit{s + i, *h};
            }
        }
    }
    return best;
}

template <bool IsWatertight>
std::optional<std::uint32_t> any(const TriangleSoA& q,
                                 std::uint32_t first,
                                 std::uint32_t count,
                                 const Rayf& ray,
                                 const WatertightRay<float>* wr) {
    const SimdLevel l = simd_level();
    const unsigned w = lanes_of(l);
    const std::uint32_t end = first + count;
    SoaChunk c;
    for (std::uint32_t s = first / TriangleSoA::group * TriangleSoA::group; s < end; s += w) {
        if constexpr (IsWatertight) {
            chunk_watertight(l, q, s / TriangleSoA::group, ray, *wr, c);
        } else {
            chunk_mt(l, q, s / TriangleSoA::group, ray, c);
        }
        for (unsigned m = c.cand & lanes_in(s, first, end); m != 0; m &= m - 1) {
            const auto i = static_cast<unsigned>(__builtin_ctz(m));
            if (accept<IsWatertight>(q, c, i, s + i, ray, wr)) {
                return s + i;
            }
        }
    }
    return std::nullopt;
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
