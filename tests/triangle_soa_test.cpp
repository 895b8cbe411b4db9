// Leaf kernels (trace/triangle_soa.h): every SIMD level the CPU runs gives, bit for bit, the
// answers of the scalar method applied slot by slot (Möller–Trumbore and watertight), including
// watertight's exact-zero fallback on shared edges and vertices; inlined into wide BVH traversal
// (trace/wide_soa.h), the answers and counts of the leaf-callback traversal.

#include "trace/triangle_soa.h"

#include "accel/any_accel.h"
#include "base/simd.h"
#include "support/accel_fixtures.h"
#include "support/ray_block.h"
#include "trace/wide_soa.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <numeric>
#include <optional>
#include <vector>

namespace rtlab {
namespace {

using Prepared = VertexTriangleMethod<float>::Prepared;

/// Triangles of the soup plus a fan of lattice triangles sharing integer edges and vertices (rays
/// through them give exact zero edge functions).
std::vector<Prepared> test_triangles(std::uint64_t seed) {
    std::vector<Prepared> out = test::random_soup(test::SoupKind::triangles, seed, 61).triangles;
    for (int x = 0; x < 3; ++x) {
        for (int y = 0; y < 3; ++y) {
            const auto fx = static_cast<float>(x), fy = static_cast<float>(y);
            out.push_back({{fx, fy, 0.5f}, {fx + 1, fy, 0.5f}, {fx + 1, fy + 1, 0.5f}});
            out.push_back({{fx, fy, 0.5f}, {fx + 1, fy + 1, 0.5f}, {fx, fy + 1, 0.5f}});
        }
    }
    return out;
}

/// Rays from the soup generator plus rays along z through lattice points and edge midpoints.
std::vector<Rayf> test_rays(std::uint64_t seed) {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, seed, 61);
    std::vector<Rayf> rays = test::random_rays(soup, seed, 150);
    for (int i = 0; i <= 6; ++i) {
        for (int j = 0; j <= 6; ++j) {
            const float x = 0.5f * static_cast<float>(i), y = 0.5f * static_cast<float>(j);
            rays.push_back({{x, y, -1.0f}, {0, 0, 1}});
            rays.push_back({{x, y, 2.0f}, {0.0f, 0.0f, -0.5f}, 0.0f, 100.0f});
        }
    }
    return rays;
}

using test::same_bits;

/// Checks every (first, count) range of slots for one method against the scalar method M.
template <class M>
void check_kernel(const std::vector<Prepared>& prims, const std::vector<Rayf>& rays) {
    // Slots in a shuffled order, as a structure's leaves would hold them.
    std::vector<std::uint32_t> slots(prims.size());
    std::iota(slots.begin(), slots.end(), 0u);
    test::Rng rng(5);
    for (std::size_t i = slots.size(); i > 1; --i) {
        std::swap(slots[i - 1], slots[rng.below(static_cast<std::uint32_t>(i))]);
    }
    constexpr bool is_wt = std::is_same_v<M, Watertight<float>>;
    const TriangleSoA soa =
        make_triangle_soa(prims, slots, is_wt ? SoaLayout::vertices : SoaLayout::edges);
    REQUIRE(soa.size() == prims.size());
    // Each slot keeps its id: the slot's own primitive, or its entry in a caller's id map.
    std::vector<std::uint32_t> global(prims.size());
    for (std::size_t i = 0; i < global.size(); ++i) {
        global[i] = static_cast<std::uint32_t>(1000 + 3 * i);
    }
    const TriangleSoA mapped =
        make_triangle_soa(prims, slots, is_wt ? SoaLayout::vertices : SoaLayout::edges, global);
    for (std::uint32_t s = 0; s < soa.size(); ++s) {
        REQUIRE(soa.id(s) == slots[s]);
        REQUIRE(mapped.id(s) == global[slots[s]]);
        if constexpr (is_wt) {
            REQUIRE(soa.vertices(s).p1.y == prims[slots[s]].p1.y);
        }
    }
    const auto n = static_cast<std::uint32_t>(prims.size());
    for (const Rayf& ray : rays) {
        const RayDataOf<M> rd = precompute_ray<M>(ray);
        for (const std::uint32_t count : {1u, 3u, 4u, 5u, 8u, 13u}) {
            for (std::uint32_t first = 0; first + count <= n; first += 7) {
                // The scalar method slot by slot.
                Rayf want_ray = ray;
                std::optional<SlotHit> want;
                std::optional<std::uint32_t> want_any;
                for (std::uint32_t s = first; s < first + count; ++s) {
                    if (const auto h = intersect_with<M>(prims[slots[s]], want_ray, rd)) {
                        want_ray.tmax = h->t;
                        want = SlotHit{s, *h};
                    }
                    if (!want_any && occluded_with<M>(prims[slots[s]], ray, rd)) {
                        want_any = s;
                    }
                }
                for (const SimdLevel l : simd_levels) {
                    if (l > simd_supported()) {
                        continue;
                    }
                    CAPTURE(simd_name(l), first, count);
                    const ScopedSimdCap cap(l);
                    Rayf got_ray = ray;
                    std::optional<SlotHit> got;
                    std::optional<std::uint32_t> got_any;
                    got = kernel_closest<M>(soa, first, count, got_ray, rd);
                    got_any = kernel_any<M>(soa, first, count, ray, rd);
                    REQUIRE(got.has_value() == want.has_value());
                    REQUIRE(got_any == want_any);
                    REQUIRE(same_bits(got_ray.tmax, want_ray.tmax));
                    if (want) {
                        REQUIRE(got->slot == want->slot);
                        REQUIRE(same_bits(got->hit.t, want->hit.t));
                        REQUIRE(same_bits(got->hit.u, want->hit.u));
                        REQUIRE(same_bits(got->hit.v, want->hit.v));
                    }
                }
            }
        }
    }
}

TEST_CASE("triangle leaf kernels of every SIMD level equal the scalar methods bit for bit",
          "[trace][simd]") {
    // Fixed seeds, so a run sees the same sets whatever shard it lands in, and one from the run's
    // seed (printed on failure), so runs keep exploring.
    const auto seed = GENERATE(1u, 2u, 3u, take(1, random(0u, 1u << 30)));
    const std::vector<Prepared> prims = test_triangles(seed);
    const std::vector<Rayf> rays = test_rays(seed);
    check_kernel<MollerTrumbore<float>>(prims, rays);
    check_kernel<Watertight<float>>(prims, rays);
}

/// wide_leaf_trace_block on triangles (all rays in one block) against
/// intersect_leaves/occluded_leaves with the leaf kernel as callback, ray by ray.
template <class M, bool IsRobust, unsigned N>
void check_inlined(const WideBvh<N>& bvh, const test::Soup& soup, const std::vector<Rayf>& rays) {
    constexpr bool is_wt = std::is_same_v<M, Watertight<float>>;
    const TriangleSoA soa = make_triangle_soa(soup.triangles, bvh.prim_ids,
                                              is_wt ? SoaLayout::vertices : SoaLayout::edges);
    test::KeepAllBlock<SlotHit> closest{rays};
    test::KeepAllBlock<std::uint32_t> any{rays};
    wide_leaf_trace_block<false, IsRobust, M>(bvh, soa, closest);
    wide_leaf_trace_block<true, IsRobust, M>(bvh, soa, any);
    for (std::size_t k = 0; k < rays.size(); ++k) {
        const Rayf& ray = rays[k];
        const RayDataOf<M> rd = precompute_ray<M>(ray);
        test::check_same_as_leaf_callbacks<IsRobust>(
            bvh, closest, any, k,
            [&](std::uint32_t first, std::uint32_t count, Rayf& r) {
                return kernel_closest<M>(soa, first, count, r, rd);
            },
            [&](std::uint32_t first, std::uint32_t count, const Rayf& r) {
                return kernel_any<M>(soa, first, count, r, rd);
            });
    }
}

TEST_CASE("leaf kernels inlined into wide BVH traversal give the leaf-callback answers and counts",
          "[trace][simd][wide]") {
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, seed, 700);
    const std::vector<Rayf> rays = test::random_rays(soup, seed, 300);
    test::for_each_wide_bvh_and_simd_level(
        {"bvh4", "bvh8", "bvh16", "bvh8,from=lbvh,max_leaf=1"}, soup.input(), [&](const auto& bvh) {
            check_inlined<MollerTrumbore<float>, false>(bvh, soup, rays);
            check_inlined<MollerTrumbore<float>, true>(bvh, soup, rays);
            check_inlined<Watertight<float>, false>(bvh, soup, rays);
            check_inlined<Watertight<float>, true>(bvh, soup, rays);
        });
}

TEST_CASE("the SIMD level can be capped and reports itself", "[simd]") {
    for (const SimdLevel l : simd_levels) {
        CHECK(parse_simd_level(simd_name(l)) == l);
        const ScopedSimdCap cap(l);
        CHECK(simd_level() == (l < simd_supported() ? l : simd_supported()));
    }
    CHECK(!parse_simd_level("avx"));
}

}  // namespace
}  // namespace rtlab
