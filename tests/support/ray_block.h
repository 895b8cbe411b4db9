#pragma once
// A RayBlock (trace/wide_soa.h) for tests: every ray of a span in one block, each ray's answer
// and traversal counts kept apart; and the check that a block traced with the leaf kernels
// inlined answers as the leaf-callback traversal does.

#include "accel/accel.h"
#include "accel/any_accel.h"
#include "base/simd.h"
#include "intersect/ray.h"
#include "trace/leaf_soa.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

namespace rtlab::test {

/// Found is SlotHit for closest-hit blocks, std::uint32_t (the slot) for any-hit ones.
template <class Found>
struct KeepAllBlock {
    std::span<const Rayf> rays;
    std::size_t begin = 0;
    std::size_t end = rays.size();
    std::vector<std::optional<Found>> found = std::vector<std::optional<Found>>(rays.size());
    std::vector<TraversalStats> counts = std::vector<TraversalStats>(rays.size());

    bool take(std::size_t i, Rayf& ray) const {
        ray = rays[i];
        return true;
    }
    void put(std::size_t i, const Found& f) { found[i] = f; }
    TraversalStats& stats(std::size_t i) { return counts[i]; }
};

/// Same bits (so -0.0 != 0.0, and NaN == NaN with the same payload).
inline bool same_bits(float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

/// Requires that ray k of closest and any (blocks traced on bvh with the leaf kernels inlined)
/// has the answers and counts of bvh's leaf-callback traversal of the same ray with the same
/// kernels: closest_kernel(first, count, ray) is a leaf's nearest std::optional<SlotHit> (and
/// shrinks ray.tmax to it), any_kernel(first, count, ray) a leaf's std::optional slot of a hit.
/// The closest hit must agree in slot and in the bits of t, u, v and the final tmax.
template <bool IsRobust, class Bvh, class ClosestKernel, class AnyKernel>
void check_same_as_leaf_callbacks(const Bvh& bvh,
                                  const KeepAllBlock<SlotHit>& closest,
                                  const KeepAllBlock<std::uint32_t>& any,
                                  std::size_t k,
                                  const ClosestKernel& closest_kernel,
                                  const AnyKernel& any_kernel) {
    const Rayf& ray = closest.rays[k];
    Rayf want_ray = ray;
    std::optional<SlotHit> want;
    TraversalStats want_st;
    bvh.template intersect_leaves<IsRobust>(
        want_ray,
        [&](std::uint32_t first, std::uint32_t count, Rayf& r) {
            const std::optional<SlotHit> h = closest_kernel(first, count, r);
            want = h ? h : want;
            return h.has_value();
        },
        want_st);
    std::optional<std::uint32_t> want_any;
    TraversalStats want_any_st;
    bvh.template occluded_leaves<IsRobust>(
        ray,
        [&](std::uint32_t first, std::uint32_t count, const Rayf& r) {
            want_any = any_kernel(first, count, r);
            return want_any.has_value();
        },
        want_any_st);
    const std::optional<SlotHit>& got = closest.found[k];
    const TraversalStats& st = closest.counts[k];
    const TraversalStats& any_st = any.counts[k];
    REQUIRE(got.has_value() == want.has_value());
    REQUIRE(same_bits(got ? got->hit.t : ray.tmax, want_ray.tmax));
    if (want) {
        REQUIRE(got->slot == want->slot);
        REQUIRE(same_bits(got->hit.t, want->hit.t));
        REQUIRE(same_bits(got->hit.u, want->hit.u));
        REQUIRE(same_bits(got->hit.v, want->hit.v));
    }
    REQUIRE(any.found[k] == want_any);
    REQUIRE(st.rays == want_st.rays);
    REQUIRE(st.nodes == want_st.nodes);
    REQUIRE(st.prims == want_st.prims);
    REQUIRE(any_st.nodes == want_any_st.nodes);
    REQUIRE(any_st.prims == want_any_st.prims);
}

/// Calls check(bvh) on the wide BVH of each spec built on input, once under each SIMD level the
/// CPU runs (capped to it); a spec that does not build a wide BVH fails the test.
template <class Check>
void for_each_wide_bvh_and_simd_level(std::initializer_list<const char*> specs,
                                      const BuildInput& input,
                                      const Check& check) {
    for (const char* spec : specs) {
        const AnyAccel accel = build_accel(spec, input);
        visit_accel(accel, [&](const auto& bvh) {
            if constexpr (is_wide_bvh<std::decay_t<decltype(bvh)>>) {
                for (const SimdLevel l : simd_levels) {
                    if (l > simd_supported()) {
                        continue;
                    }
                    CAPTURE(spec, simd_name(l));
                    const ScopedSimdCap cap(l);
                    check(bvh);
                }
            } else {
                FAIL(spec << " is not a wide BVH");
            }
        });
    }
}

}  // namespace rtlab::test
