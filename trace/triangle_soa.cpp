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

void chunk_mt(SimdLevel l, const TriangleSoA& q, std::uint32_t s, const Rayf& ray, SoaChunk& c) {
    switch (l) {
    case SimdLevel::avx512:
        return simd_avx512::soa_chunk_mt(q, s, ray, c);
    case SimdLevel::avx2:
        return simd_avx2::soa_chunk_mt(q, s, ray, c);
    case SimdLevel::sse2:
        break;
    }
    simd_sse2::soa_chunk_mt(q, s, ray, c);
}

void chunk_watertight(SimdLevel l,
                      const TriangleSoA& q,
                      std::uint32_t s,
                      const Rayf& ray,
                      const WatertightRay<float>& wr,
                      SoaChunk& c) {
    switch (l) {
    case SimdLevel::avx512:
        return simd_avx512::soa_chunk_watertight(q, s, ray, wr, c);
    case SimdLevel::avx2:
        return simd_avx2::soa_chunk_watertight(q, s, ray, wr, c);
    case SimdLevel::sse2:
        break;
    }
    simd_sse2::soa_chunk_watertight(q, s, ray, wr, c);
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
    std::optional<SlotHit> best;
    SoaChunk c;
    for (std::uint32_t s = first; s < first + count; s += w) {
        if constexpr (IsWatertight) {
            chunk_watertight(l, q, s, ray, *wr, c);
        } else {
            chunk_mt(l, q, s, ray, c);
        }
        for (unsigned m = c.cand & first_lanes(first + count - s); m != 0; m &= m - 1) {
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
    SoaChunk c;
    for (std::uint32_t s = first; s < first + count; s += w) {
        if constexpr (IsWatertight) {
            chunk_watertight(l, q, s, ray, *wr, c);
        } else {
            chunk_mt(l, q, s, ray, c);
        }
        for (unsigned m = c.cand & first_lanes(first + count - s); m != 0; m &= m - 1) {
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
    return {{a[0][s], a[1][s], a[2][s]}, {b[0][s], b[1][s], b[2][s]}, {c[0][s], c[1][s], c[2][s]}};
}

TriangleSoA make_triangle_soa(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                              std::span<const std::uint32_t> slot_ids,
                              SoaLayout layout) {
    TriangleSoA q;
    q.layout = layout;
    for (int k = 0; k < 3; ++k) {
        q.a[k].assign(slot_ids.size() + TriangleSoA::pad, 0.0f);
        q.b[k].assign(slot_ids.size() + TriangleSoA::pad, 0.0f);
        q.c[k].assign(slot_ids.size() + TriangleSoA::pad, 0.0f);
    }
    for (std::size_t s = 0; s < slot_ids.size(); ++s) {
        const auto& p = prims[slot_ids[s]];
        // The edges exactly as MollerTrumbore computes them.
        const Vec3f b = layout == SoaLayout::edges ? p.p1 - p.p0 : p.p1;
        const Vec3f c = layout == SoaLayout::edges ? p.p2 - p.p0 : p.p2;
        for (std::size_t k = 0; k < 3; ++k) {
            q.a[k][s] = p.p0[k];
            q.b[k][s] = b[k];
            q.c[k][s] = c[k];
        }
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
