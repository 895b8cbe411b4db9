// SceneTracer against brute force for every method of every family in MethodFamilyTable: a small
// seeded scene of the family traced with "brute" and with "bvh:binned" (plain and robust
// traversal) gives the same closest hits, and any hit agrees with closest-hit validity.

#include "base/prefetch.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "trace/method_families.h"
#include "trace/ray_gen.h"
#include "trace/scene_tracer.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

namespace rtlab {
namespace {

using test::Rng;

// A unit vector orthogonal to the unit vector n.
Vec3f orthogonal(Rng& rng, const Vec3f& n) {
    for (;;) {
        const Vec3f c = cross(n, rng.direction());
        if (length_squared(c) > 0.01f) {
            return normalize(c);
        }
    }
}

// Star-shaped planar polygons of 3..8 vertices in random planes; every other vertex of the even
// ones is pulled in, so half of them are concave.
void add_polygons(Scene& s, Rng& rng, const Bounds3f& space) {
    for (int i = 0; i < 60; ++i) {
        const Vec3f c = rng.point_in(space);
        const Vec3f n = rng.direction();
        const Vec3f u = orthogonal(rng, n);
        const Vec3f v = cross(n, u);
        const std::uint32_t k = 3 + rng.below(6);
        const float r = rng.uniform(0.1f, 0.5f);
        PolygonObject p;
        for (std::uint32_t j = 0; j < k; ++j) {
            const float a = 6.2831853f * static_cast<float>(j) / static_cast<float>(k);
            const float rj = (k % 2 == 0 && j % 2 == 1) ? 0.5f * r : r;
            p.vertices.push_back(c + u * (rj * std::cos(a)) + v * (rj * std::sin(a)));
        }
        s.add(std::move(p));
    }
}

// Oriented boxes with random orthonormal axes and half extents.
void add_obbs(Scene& s, Rng& rng, const Bounds3f& space) {
    for (int i = 0; i < 80; ++i) {
        ObbObject o;
        o.center = rng.point_in(space);
        const Vec3f a = rng.direction();
        const Vec3f b = orthogonal(rng, a);
        o.axes = {a, b, cross(a, b)};
        o.half = {rng.uniform(0.02f, 0.4f), rng.uniform(0.02f, 0.4f), rng.uniform(0.02f, 0.4f)};
        s.add(o);
    }
}

// A small seeded scene of `family`'s primitives, overlapping, in about [0, 4]^3 (empty for a
// family this test does not know, which the caller rejects).
Scene family_scene(std::string_view family, std::uint64_t seed) {
    Rng rng(seed);
    Scene s;
    s.materials.push_back(Material{});
    const Bounds3f space{{0, 0, 0}, {4, 4, 4}};
    if (family == "triangle") {
        MeshObject m;
        for (std::uint32_t i = 0; i < 300; ++i) {
            const Vec3f c = rng.point_in(space);
            for (int k = 0; k < 3; ++k) {
                m.mesh.positions.push_back(c + rng.direction() * 0.4f);
            }
            m.mesh.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
        }
        s.add(std::move(m));
    } else if (family == "sphere") {
        for (int i = 0; i < 100; ++i) {
            s.add(SphereObject{rng.point_in(space), rng.uniform(0.05f, 0.4f)});
        }
    } else if (family == "polygon") {
        add_polygons(s, rng, space);
    } else if (family == "box") {
        for (int i = 0; i < 100; ++i) {
            const Vec3f c = rng.point_in(space);
            const Vec3f h{rng.uniform(0, 0.3f), rng.uniform(0, 0.3f), rng.uniform(0, 0.3f)};
            s.add(BoxObject{{c - h, c + h}});
        }
    } else if (family == "obb") {
        add_obbs(s, rng, space);
    } else if (family == "cone") {
        // Cylinders, truncated and pointed cones, open and capped, in random orientations.
        for (int i = 0; i < 80; ++i) {
            ConeObject o;
            o.base = rng.point_in(space);
            o.apex = o.base + rng.direction() * rng.uniform(0.1f, 0.8f);
            o.base_radius = rng.uniform(0.02f, 0.3f);
            o.apex_radius = i % 3 == 0 ? o.base_radius : (i % 3 == 1 ? 0.0f : rng.uniform(0, 0.3f));
            o.caps = static_cast<ConeCaps>(i % 4);
            s.add(o);
        }
    } else if (family == "implicit") {
        // Both surfaces, so both shape lists of the family are traced.
        for (int i = 0; i < 6; ++i) {
            ImplicitObject o;
            o.kind = ImplicitKind::torus;
            o.center = rng.point_in(space);
            o.major = rng.uniform(0.3f, 0.6f);
            o.minor = rng.uniform(0.05f, 0.2f);
            s.add(o);
        }
        for (int i = 0; i < 4; ++i) {
            ImplicitObject o;
            o.kind = ImplicitKind::tanglecube;
            o.center = rng.point_in(space);
            o.scale = rng.uniform(0.1f, 0.2f);
            s.add(o);
        }
    }
    return s;
}

// Random rays over the scene; every fourth gets a finite window, so occlusion windows matter.
std::vector<Rayf> family_rays(const Scene& s, std::uint64_t seed) {
    std::vector<Rayf> rays = make_rays(s, RayKind::random, 1500, seed);
    Rng rng(seed + 1);
    for (std::size_t i = 0; i < rays.size(); i += 4) {
        rays[i].tmax = rng.uniform(0.5f, 4.0f);
    }
    return rays;
}

// The answers of one tracer on one ray set.
struct Answers {
    std::vector<Hit> hits;  ///< closest hits (left empty for occlusion-only methods)
    std::vector<std::uint32_t> blockers;
};

// Traces rays through a tracer of s with `accel` and `method`; checks the set labels and, for
// intersectors, that any hit agrees with closest-hit validity and per-ray counts keep the hits.
Answers trace(const Scene& s,
              const std::vector<Rayf>& rays,
              const std::string& accel,
              std::string_view family,
              std::string_view method,
              bool intersector,
              bool robust) {
    const SceneTracer tracer(s, TraceSetup{parse_accel_spec(accel), {std::string(method)}, robust});
    REQUIRE(!tracer.set_methods().empty());
    for (const std::string& label : tracer.set_methods()) {
        CHECK(label == std::string(family) + "=" + std::string(method));
    }
    Answers a;
    a.blockers.resize(rays.size());
    tracer.occluded(rays, a.blockers);
    std::vector<Hit> hits(rays.size());
    if (!intersector) {
        CHECK_THROWS_WITH(tracer.intersect(rays, hits), Catch::Contains("answers hit/no-hit only"));
        return a;
    }
    tracer.intersect(rays, hits);
    std::vector<Hit> counted(rays.size());
    std::vector<TraversalStats> per_ray(rays.size());
    tracer.intersect_counted(rays, counted, per_ray);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CAPTURE(i);
        REQUIRE((a.blockers[i] != invalid_id) == hits[i].valid());
        if (hits[i].valid()) {
            CHECK(a.blockers[i] < tracer.primitive_count());
        }
        CHECK(counted[i].prim == hits[i].prim);
        CHECK(counted[i].t == hits[i].t);
    }
    a.hits = std::move(hits);
    return a;
}

// got agrees with want: the same rays hit and are blocked, at t within 1e-6 relative; a
// different primitive is a tie (both at that t).
void check_agree(const std::vector<Rayf>& rays, const Answers& want, const Answers& got) {
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Rayf& r = rays[i];
        CAPTURE(i, r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
        REQUIRE((got.blockers[i] != invalid_id) == (want.blockers[i] != invalid_id));
        if (want.hits.empty()) {
            continue;
        }
        const Hit& w = want.hits[i];
        const Hit& g = got.hits[i];
        REQUIRE(g.valid() == w.valid());
        if (w.valid()) {
            CAPTURE(w.prim, g.prim);
            CHECK(g.t == Approx(w.t).epsilon(1e-6));
        }
    }
}

// Every ray set answer of method on a scene of family, for each structure spec (plain and robust
// traversal) against brute force.
void check_method(std::string_view family,
                  std::string_view method,
                  bool intersector,
                  const std::vector<std::string>& specs,
                  const std::vector<std::uint64_t>& seeds) {
    for (const std::uint64_t seed : seeds) {
        CAPTURE(family, method, seed);
        const Scene s = family_scene(family, seed);
        REQUIRE(!s.order.empty());  // a new family needs a scene here
        const std::vector<Rayf> rays = family_rays(s, seed);
        const Answers brute = trace(s, rays, "brute", family, method, intersector, false);
        if (intersector) {
            std::size_t hit = 0;
            for (const Hit& h : brute.hits) {
                hit += h.valid() ? 1 : 0;
            }
            CHECK(hit > rays.size() / 20);  // the scene is actually hit
            CHECK(hit < rays.size());       // and missed
        }
        for (const std::string& spec : specs) {
            for (const bool robust : {false, true}) {
                CAPTURE(spec, robust);
                check_agree(rays, brute, trace(s, rays, spec, family, method, intersector, robust));
            }
        }
    }
}

}  // namespace

TEST_CASE("every method of every family traces like brute force", "[trace][methods]") {
    std::set<std::string> seen;
    for_each_type<MethodFamilyTable>([&]<class Family>() {
        using First = std::tuple_element_t<0, typename Family::ShapeLists>;
        for_each_type<First>([&]<class M>() {
            seen.insert(std::string(Family::name) + "=" + std::string(M::name));
            check_method(Family::name, M::name, IntersectionMethod<M>, {"bvh:binned"}, {1, 2});
        });
    });
    std::size_t listed = 0;
    for (const MethodFamily& f : method_families()) {
        listed += f.methods.size();
    }
    CHECK(seen.size() == listed);
}

TEST_CASE("every registered structure, default and varied, traces every family like brute force",
          "[trace][methods][accel]") {
    // Each row with its defaults and with each parameter moved to an extreme of its range, for
    // the default method of every family (all methods run on bvh:binned in the test above).
    std::vector<std::string> specs;
    for (const AccelSpec& spec : test::registry_specs()) {
        specs.push_back(spec.canonical());
    }
    for_each_type<MethodFamilyTable>([&]<class Family>() {
        using First = std::tuple_element_t<0, typename Family::ShapeLists>;
        using Default = std::tuple_element_t<0, First>;
        check_method(Family::name, Default::name, IntersectionMethod<Default>, specs, {3});
    });
}

TEST_CASE("structures large enough to prefetch children trace like brute force", "[trace][accel]") {
    // 80,000 small triangles or spheres: with leaves of one primitive the wide and pair nodes
    // take more than prefetch_min_bytes, so traversal prefetches hit children's nodes
    // (base/prefetch.h); the answers must not change.
    constexpr std::uint32_t count = 80000;
    for (const std::string_view family : {"triangle", "sphere"}) {
        CAPTURE(family);
        Rng rng(7);
        Scene s;
        s.materials.push_back(Material{});
        const Bounds3f space{{0, 0, 0}, {4, 4, 4}};
        MeshObject m;
        for (std::uint32_t i = 0; i < count; ++i) {
            const Vec3f c = rng.point_in(space);
            if (family == "sphere") {
                s.add(SphereObject{c, rng.uniform(0.005f, 0.03f)});
                continue;
            }
            for (int k = 0; k < 3; ++k) {
                m.mesh.positions.push_back(c + rng.direction() * 0.04f);
            }
            m.mesh.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
        }
        if (family == "triangle") {
            s.add(std::move(m));
        }
        const std::vector<Rayf> rays = family_rays(s, 7);
        const std::string method = family == "sphere" ? "stable" : "moller_trumbore";
        const Answers brute = trace(s, rays, "brute", family, method, true, false);
        for (const char* spec : {"bvh8,from=lbvh,max_leaf=1", "bvh4,from=lbvh,max_leaf=1",
                                 "bvh:pair,from=lbvh,max_leaf=1"}) {
            CAPTURE(spec);
            const SceneTracer tracer(s, TraceSetup{parse_accel_spec(spec), {method}, false});
            REQUIRE(tracer.infos().size() == 1);
            CHECK(tracer.infos()[0].bytes >= prefetch_min_bytes + 4 * std::uint64_t{count});
            for (const bool robust : {false, true}) {
                CAPTURE(robust);
                check_agree(rays, brute, trace(s, rays, spec, family, method, true, robust));
            }
        }
    }
}

TEST_CASE("every method's leaf kernel on the wide layouts answers as its scalar per-id path",
          "[trace][methods][wide]") {
    // `leaves=soa` tests whole leaves with the method's leaf kernel (trace/leaf_kernel.h: the
    // hand-written ones, else the generic one over SlotPrims), `leaves=ids` one primitive id at a
    // time with the scalar method: the same hits and blockers, t, u and v bit for bit.
    const auto same_bits = [](float a, float b) {
        return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
    };
    for_each_type<MethodFamilyTable>([&]<class Family>() {
        using First = std::tuple_element_t<0, typename Family::ShapeLists>;
        for_each_type<First>([&]<class M>() {
            for (const std::uint64_t seed : {1u, 2u, 3u}) {
                const Scene s = family_scene(Family::name, seed);
                const std::vector<Rayf> rays = family_rays(s, seed);
                for (const std::string width : {"bvh8", "bvh16"}) {
                    CAPTURE(Family::name, M::name, seed, width);
                    const bool isect = IntersectionMethod<M>;
                    const Answers kernel =
                        trace(s, rays, width, Family::name, M::name, isect, false);
                    const Answers ids =
                        trace(s, rays, width + ",leaves=ids", Family::name, M::name, isect, false);
                    REQUIRE(kernel.blockers == ids.blockers);
                    for (std::size_t i = 0; i < kernel.hits.size(); ++i) {
                        const Hit& k = kernel.hits[i];
                        const Hit& d = ids.hits[i];
                        CAPTURE(i);
                        REQUIRE(k.prim == d.prim);
                        REQUIRE(
                            (same_bits(k.t, d.t) && same_bits(k.u, d.u) && same_bits(k.v, d.v)));
                    }
                }
            }
        });
    });
}

TEST_CASE("the --method name table is generated from the method lists", "[trace][methods]") {
    std::size_t k = 0;
    for_each_type<MethodFamilyTable>([&]<class Family>() {
        REQUIRE(k < method_families().size());
        const MethodFamily& f = method_families()[k++];
        CHECK(f.family == Family::name);
        using First = std::tuple_element_t<0, typename Family::ShapeLists>;
        std::vector<std::string_view> names;
        for_each_type<First>([&]<class M>() { names.push_back(M::name); });
        CHECK(f.methods == names);  // same order, so methods[0] is the list's default
        CHECK(std::set<std::string_view>(names.begin(), names.end()).size() == names.size());
    });
    CHECK(k == method_families().size());
    CHECK(std::variant_size_v<AnyPrimSet> == std::tuple_size_v<AllFamilyMethods>);
}

}  // namespace rtlab
