// The exact query mode (trace/exact_query.h, TraceSetup::exact) on every registered structure and
// parameter variant: certified closest and any hits through each one's robust traversal agree with
// CGAL's exact brute force (crosscheck/exact_triangle_oracle.h) on every adversarial ray set: hit
// or miss, the primitive under the lowest-id tie rule, and t the nearest float to the exact t.
#include "trace/exact_query.h"

#include "accel/any_accel.h"
#include "crosscheck/exact_triangle_oracle.h"
#include "scene/scene.h"
#include "support/accel_checks.h"
#include "support/exact_ray_sets.h"
#include "trace/scene_tracer.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace rtlab;
using rtlab::test::RaySet;

namespace {

/// One mesh object holding the set's triangles, so global id i is triangle i.
Scene mesh_scene(const std::vector<Trianglef>& tris) {
    Scene s;
    s.materials.push_back(Material{});
    MeshObject m;
    for (const Trianglef& t : tris) {
        const auto i = static_cast<std::uint32_t>(m.mesh.positions.size());
        m.mesh.positions.insert(m.mesh.positions.end(), {t.p0, t.p1, t.p2});
        m.mesh.triangles.push_back({i, i + 1, i + 2});
    }
    s.add(std::move(m));
    return s;
}

/// The oracle's closest hit per ray: primitive (invalid_id for a miss) and rounded t.
struct Want {
    std::vector<std::uint32_t> prim;
    std::vector<float> t;
};

Want oracle(const RaySet& set) {
    Want w;
    for (const Rayf& ray : set.rays) {
        const xcheck::ExactTriangleHits o = xcheck::exact_triangle_hits(set.tris, ray);
        w.prim.push_back(o.closest);
        w.t.push_back(o.closest != invalid_id ? o.pairs[o.closest].t : 0.0f);
    }
    return w;
}

/// Every registry row's default spec (and with leaves tested by id where the row keeps them in
/// slot order) and every parameter variant the reports run.
std::vector<std::string> every_spec() {
    std::vector<std::string> specs;
    for (const AccelEntry& e : accel_registry()) {
        specs.emplace_back(e.name);
        if (test::declares(e, "leaves")) {
            specs.push_back(std::string(e.name) + ",leaves=ids");
        }
    }
    for (const std::string_view v : accel_variants()) {
        specs.emplace_back(v);
    }
    return specs;
}

}  // namespace

TEST_CASE("exact queries agree with CGAL on every structure and adversarial ray set", "[exact]") {
    const std::vector<RaySet> sets = test::exact_ray_sets();
    std::vector<Want> wants;
    for (const RaySet& set : sets) {
        wants.push_back(oracle(set));
    }
    for (const std::string& spec : every_spec()) {
        for (std::size_t k = 0; k < sets.size(); ++k) {
            const RaySet& set = sets[k];
            TraceSetup setup;
            setup.accel = parse_accel_spec(spec);
            setup.exact = true;
            const SceneTracer tracer(mesh_scene(set.tris), setup);
            REQUIRE(tracer.set_methods() == std::vector<std::string>{"triangle=exact"});
            std::vector<Hit> hits(set.rays.size());
            std::vector<std::uint32_t> blockers(set.rays.size());
            tracer.intersect(set.rays, hits);
            tracer.occluded(set.rays, blockers);
            std::size_t wrong_closest = 0, wrong_any = 0, hit_rays = 0;
            std::string first;
            for (std::size_t i = 0; i < set.rays.size(); ++i) {
                const std::uint32_t want = wants[k].prim[i];
                // The nearest float to the exact t (a zero t has no sign to agree on).
                const bool same =
                    hits[i].prim == want && (want == invalid_id || hits[i].t == wants[k].t[i]);
                if (!same && first.empty()) {
                    std::ostringstream os;
                    os << std::hexfloat << "ray " << i << ": prim " << hits[i].prim << " t "
                       << hits[i].t << ", oracle prim " << want << " t " << wants[k].t[i];
                    first = os.str();
                }
                wrong_closest += same ? 0 : 1;
                wrong_any += (blockers[i] != invalid_id) != (want != invalid_id) ? 1 : 0;
                hit_rays += want != invalid_id ? 1 : 0;
            }
            INFO(spec << " on " << set.name << ": " << set.rays.size() << " rays, " << hit_rays
                      << " hits; " << first);
            CHECK(wrong_closest == 0);
            CHECK(wrong_any == 0);
        }
    }
}

TEST_CASE("exact queries count the tests that fell back to exact arithmetic", "[exact]") {
    const RaySet set = test::lattice_set(21, 1.0f);
    TraceSetup setup;
    setup.accel = parse_accel_spec("bvh8");
    setup.exact = true;
    const SceneTracer tracer(mesh_scene(set.tris), setup);
    const ExactCounts c = tracer.exact_counts(set.rays, false);
    CHECK(c.rays == set.rays.size());
    CHECK(c.tests >= c.rays / 2);
    // Rays aimed exactly at shared vertices and edges: some tests cannot be decided in double.
    CHECK(c.fallbacks > 0);
    CHECK(c.fallback_rays > 0);
    CHECK(c.fallback_rays <= c.rays);
}

TEST_CASE("exact mode refuses scenes and set-ups it cannot certify", "[exact]") {
    Scene spheres = mesh_scene(test::random_set(3).tris);
    spheres.add(SphereObject{{0, 0, 0}, 1.0f});
    TraceSetup setup;
    setup.exact = true;
    CHECK_THROWS_AS(SceneTracer(spheres, setup), std::invalid_argument);
    setup.methods = {"watertight"};
    CHECK_THROWS_AS(SceneTracer(mesh_scene(test::random_set(3).tris), setup),
                    std::invalid_argument);
}
