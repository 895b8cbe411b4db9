#pragma once
// The one table of leaf kernels: per intersection method, the slot-ordered leaf data a tracer
// keeps for a structure that hands out whole leaves (LeafRangeAccel) and so the kernel that tests
// a leaf of it. A method without an entry takes the generic kernel over SlotPrims<M>
// (trace/slot_prims.h), so every method runs on every such layout through the same leaf path. A
// hand-written SIMD kernel is one entry here (its data type, how to fill it, simd = true) plus its
// kernel file, which defines leaf_closest and leaf_any over that data (and the method's RayDataOf)
// in every SIMD level's namespace (base/simd_each_level.inc) and is included below; on wide BVHs
// the tracer inlines it into one traversal per SIMD level (trace/wide_soa.h).

#include "base/simd.h"
#include "intersect/method.h"
#include "trace/slot_prims.h"
#include "trace/sphere_soa_kernels.h"
#include "trace/triangle_soa_kernels.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <optional>
#include <span>

namespace rtlab {

/// Method M's leaf data `Data` and `make(prims, slot_ids, ids)`, which fills it with prims in the
/// slot order slot_ids (accel/accel.h, padding_slot entries included), each slot with the id
/// ids[slot_ids[s]]; `simd` when the kernel is a hand-written one compiled per SIMD level.
/// Default: the generic kernel over SlotPrims<M>.
template <class M>
struct LeafKernel {
    using Data = SlotPrims<M>;
    static constexpr bool simd = false;
    static Data make(std::span<const typename M::Prepared> prims,
                     std::span<const std::uint32_t> slot_ids,
                     std::span<const std::uint32_t> ids) {
        return make_slot_prims<M>(prims, slot_ids, ids);
    }
};

/// A hand-written triangle kernel on 4 or 8 lanes over TriangleSoA rows in `Layout`
/// (trace/triangle_soa_kernels.inc).
template <SoaLayout Layout>
struct TriangleSoaKernel {
    using Data = TriangleSoA;
    static constexpr bool simd = true;
    static Data make(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                     std::span<const std::uint32_t> slot_ids,
                     std::span<const std::uint32_t> ids) {
        return make_triangle_soa(prims, slot_ids, Layout, ids);
    }
};

/// Möller–Trumbore over edges.
template <>
struct LeafKernel<MollerTrumbore<float>> : TriangleSoaKernel<SoaLayout::edges> {};

/// Watertight over vertices.
template <>
struct LeafKernel<Watertight<float>> : TriangleSoaKernel<SoaLayout::vertices> {};

/// SphereStable on 4 or 8 lanes (trace/sphere_soa_kernels.inc).
template <>
struct LeafKernel<SphereStable<float>> {
    using Data = SphereSoA;
    static constexpr bool simd = true;
    static Data make(std::span<const PreparedSphere<float>> prims,
                     std::span<const std::uint32_t> slot_ids,
                     std::span<const std::uint32_t> ids) {
        return make_sphere_soa(prims, slot_ids, ids);
    }
};

/// Whether the generic kernel tests a leaf of `count` slots of a method with lanes by its lane
/// test: when it fills at least half a lane group (below that, slot by slot measured faster on
/// kd-trees).
inline bool lane_leaf(std::uint32_t count) {
    return 2 * count >= lane_count;
}

/// For a method with lanes: calls visit(group, base, bits) for each lane group of q holding slots
/// of [first, first + count), in order, lane k of the group being slot base + k and bits its
/// lanes inside that range, and returns the first slot it returns (nullopt if none).
template <class M, class Visit>
std::optional<std::uint32_t> for_lane_groups(const SlotPrims<M>& q,
                                             std::uint32_t first,
                                             std::uint32_t count,
                                             const Visit& visit) {
    const std::uint32_t end = first + count;
    for (std::uint32_t base = first / lane_count * lane_count; base < end; base += lane_count) {
        const std::uint32_t lo = first > base ? first - base : 0;
        const std::uint32_t hi = std::min(end - base, lane_count);
        const unsigned in_leaf = ((1u << hi) - 1u) & ~((1u << lo) - 1u);
        if (const std::optional<std::uint32_t> s =
                visit(q.lanes[base / lane_count], base, in_leaf)) {
            return s;
        }
    }
    return std::nullopt;
}

/// For a LaneMethod M: calls decide(s, hits, k) for the slots s of [first, first + count) whose
/// lane test with ray's window (at the time their group is tested) reports a hit, in slot order,
/// s in lane k of `hits`, and returns the first for which it returns true (nullopt if none).
template <class M, class Decide>
std::optional<std::uint32_t> lane_candidates(const SlotPrims<M>& q,
                                             std::uint32_t first,
                                             std::uint32_t count,
                                             const Rayf& ray,
                                             const RayDataOf<M>& rd,
                                             const Decide& decide) {
    const auto group = [&](const typename M::Lanes& g, std::uint32_t base,
                           unsigned in_leaf) -> std::optional<std::uint32_t> {
        const LaneHit<FloatLanes> hits = lane_test<M>(g, ray, rd);
        for (unsigned m = in_leaf & lane_bits(hits.hit); m != 0; m &= m - 1) {
            const auto k = static_cast<unsigned>(std::countr_zero(m));
            if (decide(base + k, hits, k)) {
                return base + k;
            }
        }
        return std::nullopt;
    };
    return for_lane_groups(q, first, count, group);
}

/// The leaf data of M's kernel.
template <class M>
using LeafData = typename LeafKernel<M>::Data;

/// Closest hit of M's leaf kernel among slots [first, first + count) of q, exactly as M's scalar
/// test on each slot in order, each hit shrinking ray.tmax (which this does too), rd the ray's
/// set-up (precompute_ray<M>); nullopt if none. For callers outside SIMD-level code: a
/// hand-written kernel's level is chosen per call.
template <class M>
std::optional<SlotHit> kernel_closest(const LeafData<M>& q,
                                      std::uint32_t first,
                                      std::uint32_t count,
                                      Rayf& ray,
                                      const RayDataOf<M>& rd) {
    if constexpr (!LeafKernel<M>::simd) {
        // The generic kernel, inlined into the traversal that calls it: the slots in order, or,
        // for a method with a lane form, the candidates of its lane test in order.
        std::optional<SlotHit> best;
        const auto test = [&](std::uint32_t s) {
            if (const auto h = intersect_with<M>(q.prims[s], ray, rd)) {
                ray.tmax = h->t;
                best = SlotHit{s, *h};
            }
            return false;
        };
        if constexpr (LaneMethod<M>) {
            if (lane_leaf(count)) {
                // A lane's hit is the scalar test's with the group's window; a window shrunk
                // since then keeps it exactly when its t is still inside (LaneMethod).
                const auto take = [&](std::uint32_t s, const LaneHit<FloatLanes>& h, unsigned k) {
                    if (h.t[k] <= ray.tmax) {
                        ray.tmax = h.t[k];
                        best = SlotHit{s, PrimHit<float>{h.t[k], h.u[k], h.v[k]}};
                    }
                    return false;
                };
                lane_candidates(q, first, count, ray, rd, take);
                return best;
            }
        }
        for (std::uint32_t s = first; s < first + count; ++s) {
            test(s);
        }
        return best;
    } else {
        switch (simd_level()) {
        case SimdLevel::avx512:
            return simd_avx512::leaf_closest(q, first, count, ray, rd);
        case SimdLevel::avx2:
            return simd_avx2::leaf_closest(q, first, count, ray, rd);
        case SimdLevel::sse2:
            break;
        }
        return simd_sse2::leaf_closest(q, first, count, ray, rd);
    }
}

/// The first slot of [first, first + count) of q that M's scalar any-hit test reports, or
/// nullopt; the level chosen per call as kernel_closest.
template <class M>
std::optional<std::uint32_t> kernel_any(const LeafData<M>& q,
                                        std::uint32_t first,
                                        std::uint32_t count,
                                        const Rayf& ray,
                                        const RayDataOf<M>& rd) {
    if constexpr (!LeafKernel<M>::simd) {
        const auto test = [&](std::uint32_t s) { return occluded_with<M>(q.prims[s], ray, rd); };
        if constexpr (HasLanes<M>) {
            if (lane_leaf(count)) {
                const auto group = [&](const typename M::Lanes& g, std::uint32_t base,
                                       unsigned in_leaf) -> std::optional<std::uint32_t> {
                    const unsigned m = in_leaf & lane_bits(lane_occluded<M>(g, ray, rd));
                    if (m == 0) {
                        return std::nullopt;
                    }
                    return base + static_cast<std::uint32_t>(std::countr_zero(m));
                };
                return for_lane_groups(q, first, count, group);
            }
        }
        for (std::uint32_t s = first; s < first + count; ++s) {
            if (test(s)) {
                return s;
            }
        }
        return std::nullopt;
    } else {
        switch (simd_level()) {
        case SimdLevel::avx512:
            return simd_avx512::leaf_any(q, first, count, ray, rd);
        case SimdLevel::avx2:
            return simd_avx2::leaf_any(q, first, count, ray, rd);
        case SimdLevel::sse2:
            break;
        }
        return simd_sse2::leaf_any(q, first, count, ray, rd);
    }
}

}  // namespace rtlab
