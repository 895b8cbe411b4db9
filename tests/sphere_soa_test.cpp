// Sphere leaf kernels (trace/sphere_soa.h): every SIMD level the CPU runs gives, bit for bit, the
// answers of SphereStable<float> applied slot by slot (random, tangent and grazing rays, origins
// inside and on spheres, the q == 0 root, overflowing directions); inlined into wide BVH traversal
// (trace/wide_soa.h), the answers and counts of the leaf-callback traversal; and traced by
// SceneTracer on bvh4/bvh8 through the SphereSoA, the hits of the per-id path and of brute force.

#include "trace/sphere_soa.h"

#include "accel/any_accel.h"
#include "base/simd.h"
#include "datasets_gen/sphere_flake.h"
#include "support/accel_fixtures.h"
#include "support/ray_block.h"
#include "trace/scene_tracer.h"
#include "trace/wide_soa.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace rtlab {
namespace {

using M = SphereStable<float>;
using Prepared = PreparedSphere<float>;

using test::same_bits;

/// Random overlapping spheres in [0, 4]^3 of radii from tiny to large, a duplicate, the unit
/// sphere at the origin and a sphere of integer centre (exact tangents and surface points).
std::vector<Prepared> test_spheres(std::uint64_t seed, std::uint32_t count) {
    test::Rng rng(seed);
    std::vector<Prepared> out;
    for (std::uint32_t i = 0; i < count; ++i) {
        const float r = rng.below(8) == 0 ? rng.uniform(1e-4f, 0.01f) : rng.uniform(0.05f, 0.8f);
        out.push_back(M::prepare({rng.point_in({{0, 0, 0}, {4, 4, 4}}), r}));
    }
    out.push_back(out[count / 2]);
    out.push_back(M::prepare({{0, 0, 0}, 1.0f}));
    out.push_back(M::prepare({{2, 2, 2}, 0.5f}));
    return out;
}

/// Rays at the spheres: towards a random point, tangent and grazing (the line at the radius
/// from the centre, one ulp-scale nudge in or out), from inside, from the surface, the tangent
/// line through its origin (q == 0), and directions so long that a = dir . dir overflows.
std::vector<Rayf> test_rays(const std::vector<Prepared>& spheres, std::uint64_t seed) {
    test::Rng rng(seed ^ 0x5EED);
    std::vector<Rayf> rays;
    const Bounds3f outer{{-2, -2, -2}, {6, 6, 6}};
    for (std::uint32_t i = 0; i < 400; ++i) {
        const Prepared& p = spheres[rng.below(static_cast<std::uint32_t>(spheres.size()))];
        const Vec3f d = rng.direction();
        Rayf r;
        switch (i % 8) {
        case 0:  // from outside towards a point of the scene
            r.org = rng.point_in(outer);
            r.dir = rng.point_in({{0, 0, 0}, {4, 4, 4}}) - r.org;
            break;
        case 1:
        case 2: {  // tangent or grazing: the line passes at (1 + e) r from the centre
            Vec3f n = cross(d, rng.direction());
            n = normalize(n);
            const float e = i % 8 == 1 ? 0.0f : rng.uniform(-3e-7f, 3e-7f);
            r.org = p.center + n * (p.radius * (1.0f + e)) - d * rng.uniform(0.5f, 3.0f);
            r.dir = d * rng.uniform(0.5f, 2.0f);
            break;
        }
        case 3:  // from inside
            r.org = p.center + d * (p.radius * rng.uniform(0.0f, 0.9f));
            r.dir = rng.direction();
            break;
        case 4:  // from the surface, inwards or outwards
            r.org = p.center + d * p.radius;
            r.dir = rng.direction();
            break;
        case 5:  // finite window that may start behind the origin
            r.org = rng.point_in(outer);
            r.dir = rng.point_in({{0, 0, 0}, {4, 4, 4}}) - r.org;
            r.tmin = rng.uniform(-0.5f, 0.5f);
            r.tmax = r.tmin + rng.uniform(0.0f, 1.0f);
            break;
        case 6:  // axis-aligned through the scene
            r.org = rng.point_in(outer);
            r.dir = {0, 0, 0};
            r.dir[rng.below(3)] = rng.below(2) ? 1.0f : -1.0f;
            break;
        default:  // a long direction: a near or past float's range
            r.org = rng.point_in(outer);
            r.dir = rng.direction() * (rng.below(2) ? 1e19f : 3e19f);
            break;
        }
        rays.push_back(r);
    }
    // Exact tangent lines of the unit sphere at the origin and of the sphere at (2, 2, 2), from
    // their tangent points (q == 0: t0 = t1 = -0) and from before them.
    rays.push_back({{1, 0, 0}, {0, 1, 0}});
    rays.push_back({{0, -1, 0}, {0, 0, -2}, -1.0f, 1.0f});
    rays.push_back({{2.5f, 2, 2}, {0, 0, 1}});
    rays.push_back({{2.5f, 2, 0}, {0, 0, 1}});
    rays.push_back({{2, 1.5f, -3}, {0, 0, 0.5f}});
    return rays;
}

/// The scalar method on slots [first, first + count): the closest hit (shrinking the window) and
/// the first occluding slot.
struct Scalar {
    std::optional<SlotHit> closest;
    float tmax;
    std::optional<std::uint32_t> any;
};
Scalar scalar(const std::vector<Prepared>& prims,
              const std::vector<std::uint32_t>& slots,
              std::uint32_t first,
              std::uint32_t count,
              const Rayf& ray) {
    const SphereRay<float> rd = M::precompute(ray);
    Scalar want{std::nullopt, ray.tmax, std::nullopt};
    Rayf r = ray;
    for (std::uint32_t s = first; s < first + count; ++s) {
        if (const auto h = M::intersect(prims[slots[s]], r, rd)) {
            r.tmax = h->t;
            want.closest = SlotHit{s, *h};
        }
        if (!want.any && M::occluded(prims[slots[s]], ray, rd)) {
            want.any = s;
        }
    }
    want.tmax = r.tmax;
    return want;
}

TEST_CASE("sphere leaf kernels of every SIMD level equal SphereStable slot by slot, bit for bit",
          "[trace][simd][sphere]") {
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    const std::vector<Prepared> prims = test_spheres(seed, 40);
    const std::vector<Rayf> rays = test_rays(prims, seed);
    // Slots in a shuffled order, as a structure's leaves would hold them.
    std::vector<std::uint32_t> slots(prims.size());
    std::iota(slots.begin(), slots.end(), 0u);
    test::Rng rng(seed + 7);
    for (std::size_t i = slots.size(); i > 1; --i) {
        std::swap(slots[i - 1], slots[rng.below(static_cast<std::uint32_t>(i))]);
    }
    const SphereSoA soa = make_sphere_soa(prims, slots);
    std::vector<std::uint32_t> global(prims.size());
    for (std::size_t i = 0; i < global.size(); ++i) {
        global[i] = static_cast<std::uint32_t>(1000 + 3 * i);
    }
    const SphereSoA mapped = make_sphere_soa(prims, slots, global);
    const auto n = soa.size();
    REQUIRE(n == prims.size());
    REQUIRE(soa.data.size() == (n + 3) / 4 * 20 + 20);
    for (std::uint32_t s = 0; s < n; ++s) {
        REQUIRE(soa.id(s) == slots[s]);
        REQUIRE(mapped.id(s) == global[slots[s]]);
        REQUIRE(same_bits(soa.at(s, 1), prims[slots[s]].center.y));
        REQUIRE(same_bits(soa.at(s, 3), prims[slots[s]].radius2));
    }
    std::size_t hits = 0, inside = 0;
    for (const Rayf& ray : rays) {
        const SphereRay<float> rd = M::precompute(ray);
        for (std::uint32_t count = 1; count <= 9; ++count) {
            for (std::uint32_t first = 0; first + count <= n; first += 1 + count / 3) {
                const Scalar want = scalar(prims, slots, first, count, ray);
                hits += want.closest ? 1 : 0;
                inside += want.closest && want.closest->hit.t > 0 &&
                          M::roots(prims[slots[want.closest->slot]], ray, rd)->first < ray.tmin;
                for (const SimdLevel l : simd_levels) {
                    if (l > simd_supported()) {
                        continue;
                    }
                    CAPTURE(simd_name(l), first, count, ray.org.x, ray.org.y, ray.org.z, ray.dir.x,
                            ray.dir.y, ray.dir.z, ray.tmin, ray.tmax);
                    const ScopedSimdCap cap(l);
                    Rayf got_ray = ray;
                    const auto got = kernel_closest<M>(soa, first, count, got_ray, rd);
                    REQUIRE(got.has_value() == want.closest.has_value());
                    REQUIRE(same_bits(got_ray.tmax, want.tmax));
                    if (got) {
                        REQUIRE(got->slot == want.closest->slot);
                        REQUIRE(same_bits(got->hit.t, want.closest->hit.t));
                        REQUIRE(same_bits(got->hit.u, want.closest->hit.u));
                        REQUIRE(same_bits(got->hit.v, want.closest->hit.v));
                    }
                    REQUIRE(kernel_any<M>(soa, first, count, ray, rd) == want.any);
                }
            }
        }
    }
    CHECK(hits > 1000);   // the rays do hit
    CHECK(inside > 100);  // and leave spheres their origin is in
}

/// wide_leaf_trace_block on spheres (all rays in one block) against
/// intersect_leaves/occluded_leaves with the leaf kernel as callback, and the closest hit against
/// the scalar method on every sphere (brute force), ray by ray.
template <bool IsRobust, unsigned N>
void check_inlined(const WideBvh<N>& bvh,
                   const std::vector<Prepared>& prims,
                   const std::vector<Rayf>& rays) {
    const SphereSoA soa = make_sphere_soa(prims, bvh.prim_ids);
    test::KeepAllBlock<SlotHit> closest{rays};
    test::KeepAllBlock<std::uint32_t> any{rays};
    wide_leaf_trace_block<false, IsRobust, M>(bvh, soa, closest);
    wide_leaf_trace_block<true, IsRobust, M>(bvh, soa, any);
    for (std::size_t k = 0; k < rays.size(); ++k) {
        const Rayf& ray = rays[k];
        const SphereRay<float> rd = M::precompute(ray);
        test::check_same_as_leaf_callbacks<IsRobust>(
            bvh, closest, any, k,
            [&](std::uint32_t first, std::uint32_t count, Rayf& r) {
                return kernel_closest<M>(soa, first, count, r, rd);
            },
            [&](std::uint32_t first, std::uint32_t count, const Rayf& r) {
                return kernel_any<M>(soa, first, count, r, rd);
            });
        const std::optional<SlotHit>& got = closest.found[k];
        const std::optional<std::uint32_t>& got_any = any.found[k];
        const float got_tmax = got ? got->hit.t : ray.tmax;
        // Brute force: the nearest t of any sphere (ties may name another sphere and, at t = 0,
        // differ in the zero's sign: the last of equal roots is kept).
        Rayf brute_ray = ray;
        bool brute_hit = false;
        for (const Prepared& p : prims) {
            const auto h = is_valid(ray) ? M::intersect(p, brute_ray, rd) : std::nullopt;
            if (h) {
                brute_ray.tmax = h->t;
                brute_hit = true;
            }
        }
        REQUIRE(got.has_value() == brute_hit);
        REQUIRE(got_any.has_value() == brute_hit);
        REQUIRE(got_tmax == brute_ray.tmax);  // -0 and +0 tie (huge directions)
    }
}

TEST_CASE("sphere leaf kernels inlined into wide BVH traversal give the leaf-callback answers",
          "[trace][simd][wide][sphere]") {
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    const std::vector<Prepared> prims = test_spheres(seed, 500);
    std::vector<Bounds3f> boxes;
    for (const Prepared& p : prims) {
        boxes.push_back(M::bounds(p));
    }
    const std::vector<Rayf> rays = test_rays(prims, seed);
    test::for_each_wide_bvh_and_simd_level(
        {"bvh4", "bvh8", "bvh16", "bvh8,from=lbvh,max_leaf=1", "bvh16,bounds=dop14"},
        BuildInput{boxes, {}}, [&](const auto& bvh) {
            check_inlined<false>(bvh, prims, rays);
            check_inlined<true>(bvh, prims, rays);
        });
}

/// The closest hits and blockers of rays through a tracer of scene.
struct Traced {
    std::vector<Hit> hits;
    std::vector<std::uint32_t> blockers;
    std::size_t soa_slots = 0;   ///< slots of the sphere set's SphereSoA (0: another path)
    std::size_t leaf_bytes = 0;  ///< SceneTracer::leaf_bytes
};
Traced trace(const Scene& scene, const std::vector<Rayf>& rays, const std::string& spec) {
    const SceneTracer tracer(scene, TraceSetup{parse_accel_spec(spec), {"stable"}, false});
    Traced t;
    for (const AnyPrimSet& set : tracer.sets()) {
        std::visit(
            [&](const auto& s) {
                if constexpr (std::is_same_v<typename std::decay_t<decltype(s)>::Method, M>) {
                    t.soa_slots = s.soa.size();
                }
            },
            set);
    }
    t.leaf_bytes = tracer.leaf_bytes();
    t.hits.resize(rays.size());
    t.blockers.resize(rays.size());
    tracer.intersect(rays, t.hits);
    tracer.occluded(rays, t.blockers);
    return t;
}

TEST_CASE("SceneTracer traces spheres on bvh4/bvh8 through the SphereSoA like the per-id path",
          "[trace][sphere][wide]") {
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    const std::vector<Prepared> prims = test_spheres(seed, 2000);
    Scene scene;
    scene.materials.push_back(Material{});
    for (const Prepared& p : prims) {
        scene.add(SphereObject{p.center, p.radius});
    }
    const std::vector<Rayf> rays = test_rays(prims, seed);
    const Traced brute = trace(scene, rays, "brute");
    // The wide BVHs inline the kernel; the pair BVH and the kd-tree (slots repeat primitives)
    // call it per leaf.
    for (const std::string spec : {"bvh4", "bvh8", "bvh16", "bvh8,from=pbinned", "bvh:pair",
                                   "kdtree:sah", "bvh16,bounds=dop14", "bvh8,bounds=dop14"}) {
        CAPTURE(spec);
        const Traced ids = trace(scene, rays, spec + ",leaves=ids");
        const Traced soa = trace(scene, rays, spec);
        CHECK(ids.soa_slots == 0);
        CHECK(soa.soa_slots >= prims.size());  // the leaf kernel path is taken
        // Leaf data: the prepared spheres and the id map, or the blocks (padding slots and the
        // zero group included).
        CHECK(ids.leaf_bytes == prims.size() * (sizeof(Prepared) + sizeof(std::uint32_t)));
        CHECK(soa.leaf_bytes ==
              ((soa.soa_slots + 3) / 4 + 1) * SphereSoA::group_floats * sizeof(float));
        std::size_t hit = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            CAPTURE(i);
            const Hit& w = ids.hits[i];
            const Hit& g = soa.hits[i];
            REQUIRE(g.prim == w.prim);  // same tree, same order of tests: same sphere
            REQUIRE(same_bits(g.t, w.t));
            REQUIRE(same_bits(g.u, w.u));
            REQUIRE(same_bits(g.v, w.v));
            REQUIRE(g.valid() == brute.hits[i].valid());
            REQUIRE(g.t == brute.hits[i].t);  // another order: only the sign of a 0 may differ
            REQUIRE((soa.blockers[i] != invalid_id) == g.valid());
            hit += g.valid() ? 1 : 0;
        }
        CHECK(hit > rays.size() / 4);
    }
}

TEST_CASE("diagonal slabs find the same sphere flake hits with fewer node and leaf visits",
          "[trace][sphere][wide]") {
    Scene scene;
    scene.materials.push_back(Material{});
    std::vector<Prepared> prims;
    for (const gen::FlakeSphere& f : gen::sphere_flake(3)) {
        const Vec3f c{static_cast<float>(f.center.x), static_cast<float>(f.center.y),
                      static_cast<float>(f.center.z)};
        const auto r = static_cast<float>(f.radius);
        scene.add(SphereObject{c, r});
        prims.push_back(M::prepare(Sphere<float>{c, r}));
    }
    const std::vector<Rayf> rays = test_rays(prims, 7);
    const auto counted = [&](const std::string& spec, std::vector<Hit>& hits) {
        const SceneTracer tracer(scene, TraceSetup{parse_accel_spec(spec), {"stable"}, false});
        hits.resize(rays.size());
        TraversalStats st;
        tracer.intersect(rays, hits, &st);
        return st;
    };
    std::vector<Hit> box_hits, diag_hits;
    const TraversalStats box = counted("bvh16", box_hits);
    const TraversalStats diag = counted("bvh16,bounds=dop14", diag_hits);
    std::size_t hit = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CAPTURE(i);
        REQUIRE(diag_hits[i].prim == box_hits[i].prim);
        REQUIRE(diag_hits[i].t == box_hits[i].t);
        hit += box_hits[i].valid() ? 1 : 0;
    }
    CHECK(hit > rays.size() / 4);
    // Machine-independent counts: the slabs cut the boxes' corners around the flake's clusters.
    CHECK(diag.nodes < box.nodes);
    CHECK(diag.prims < box.prims);
}

}  // namespace
}  // namespace rtlab
