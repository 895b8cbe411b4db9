// bvh:sbvh (spatial splits): with the triangles' clip function it cuts primitives into several
// leaves, every point of every triangle stays inside a leaf box that lists it, and binary and
// wide layouts built from it answer as brute force does.

#include "accel/any_accel.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "trace/clip.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace rtlab {
namespace {

/// `count` slivers across the unit cube (two far vertices, the third next to one of them): long
/// thin triangles whose boxes overlap, the case spatial splits are for.
test::Soup sliver_soup(std::uint64_t seed, std::uint32_t count) {
    test::Rng rng(seed);
    test::Soup s;
    s.kind = test::SoupKind::triangles;
    const Bounds3f cube{{0, 0, 0}, {1, 1, 1}};
    for (std::uint32_t i = 0; i < count; ++i) {
        const Vec3f a = rng.point_in(cube), b = rng.point_in(cube);
        const Vec3f c = b + Vec3f{rng.uniform(-0.02f, 0.02f), rng.uniform(-0.02f, 0.02f),
                                  rng.uniform(-0.02f, 0.02f)};
        s.triangles.push_back(MollerTrumbore<float>::prepare({a, b, c}));
        s.boxes.push_back(MollerTrumbore<float>::bounds(s.triangles.back()));
    }
    return s;
}

/// The soup's boxes with the exact clip of its triangles.
BuildInput clipped_input(const test::Soup& s) {
    return {s.boxes, [&s](std::uint32_t id, const Bounds3f& box) {
                const auto& t = s.triangles[id];
                return clip_triangle_bounds(t.p0, t.p1, t.p2, box);
            }};
}

/// Checks that every sample point of every triangle (vertices, edge midpoints and `interior`
/// random interior points) lies in the box of some leaf that lists the triangle.
void check_parts_cover(const Bvh& bvh, const test::Soup& s, int interior = 16) {
    std::vector<std::vector<Bounds3f>> leaf_boxes(s.boxes.size());
    for (const BvhNode& n : bvh.nodes) {
        if (n.is_leaf()) {
            for (std::uint32_t k = n.first; k < n.first + n.prim_count(); ++k) {
                leaf_boxes[bvh.prim_ids[k]].push_back(n.bounds());
            }
        }
    }
    test::Rng rng(3);
    for (std::uint32_t id = 0; id < s.triangles.size(); ++id) {
        const auto& t = s.triangles[id];
        // Midpoints as halves added: no overflow at coordinates near the float range's ends.
        std::vector<Vec3f> points{t.p0,
                                  t.p1,
                                  t.p2,
                                  t.p0 * 0.5f + t.p1 * 0.5f,
                                  t.p1 * 0.5f + t.p2 * 0.5f,
                                  t.p2 * 0.5f + t.p0 * 0.5f};
        for (int k = 0; k < interior; ++k) {
            float u = rng.uniform(), v = rng.uniform();
            if (u + v > 1) {
                u = 1 - u;
                v = 1 - v;
            }
            points.push_back(t.p0 + (t.p1 - t.p0) * u + (t.p2 - t.p0) * v);
        }
        for (const Vec3f& p : points) {
            CAPTURE(id, p.x, p.y, p.z);
            CHECK(std::any_of(leaf_boxes[id].begin(), leaf_boxes[id].end(),
                              [&](const Bounds3f& b) { return b.contains(p); }));
        }
    }
}

}  // namespace

TEST_CASE("spatial splits cut slivers into parts that still cover them", "[accel][bvh][sbvh]") {
    const test::Soup soup = sliver_soup(11, 800);
    const BuildInput in = clipped_input(soup);
    const Bvh sbvh = std::get<Bvh>(build_accel("bvh:sbvh,max_leaf=4,ct=1", in));
    const Bvh binned = std::get<Bvh>(build_accel("bvh:binned,max_leaf=4,ct=1", in));
    REQUIRE(sbvh.validate().empty());
    const AccelInfo si = sbvh.info(), bi = binned.info();
    CAPTURE(si.refs_per_prim, si.sah_cost, bi.sah_cost);
    CHECK(si.refs_per_prim > 1.05);    // primitives were cut
    CHECK(bi.refs_per_prim == 1.0);    // object splits never cut
    CHECK(si.sah_cost < bi.sah_cost);  // and it paid by the SAH's own measure
    CHECK(sbvh == std::get<Bvh>(build_accel("bvh:sbvh,max_leaf=4,ct=1", in)));  // deterministic
    check_parts_cover(sbvh, soup);
}

TEST_CASE("spatial splits stay off node boxes wider than the float range", "[accel][bvh][sbvh]") {
    // Slivers from -3e38 to 3e38 on x: the root's extent overflows to infinity (no spatial bins
    // on that axis), and the tree must still be valid and cover every triangle.
    test::Soup soup;
    soup.kind = test::SoupKind::triangles;
    test::Rng rng(4);
    for (int i = 0; i < 200; ++i) {
        const float y = rng.uniform(0, 1), z = rng.uniform(0, 1);
        const Trianglef t{{-3e38f, y, z}, {3e38f, y + 0.01f, z}, {3e38f, y, z + 0.01f}};
        soup.triangles.push_back(MollerTrumbore<float>::prepare(t));
        soup.boxes.push_back(MollerTrumbore<float>::bounds(soup.triangles.back()));
    }
    const Bvh bvh = std::get<Bvh>(build_accel("bvh:sbvh,max_leaf=2", clipped_input(soup)));
    REQUIRE(bvh.validate().empty());
    check_parts_cover(bvh, soup, 0);  // interior points would overflow
}

TEST_CASE("spatial-split trees are the same for any thread count", "[accel][bvh][sbvh]") {
    // Large enough for the top subtrees to build as parallel tasks and be spliced.
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 8, 40000);
    const BuildInput in = clipped_input(soup);
    const Bvh one = std::get<Bvh>(build_accel("bvh:sbvh,threads=1", in));
    REQUIRE(one.validate().empty());
    CHECK(one.info().refs_per_prim > 1.0);
    for (const std::string threads : {"2", "0"}) {
        CAPTURE(threads);
        CHECK(std::get<Bvh>(build_accel("bvh:sbvh,threads=" + threads, in)) == one);
    }
}

TEST_CASE("spatial-split trees answer as brute force, binary and wide", "[accel][bvh][sbvh]") {
    const bool slivers = GENERATE(true, false);
    const test::Soup soup =
        slivers ? sliver_soup(5, 500) : test::random_soup(test::SoupKind::triangles, 5, 2000);
    const BuildInput in = clipped_input(soup);
    const std::vector<Rayf> rays = test::random_rays(soup, 17, 3000);
    check_parts_cover(std::get<Bvh>(build_accel("bvh:sbvh", in)), soup);
    for (const std::string spec :
         {"bvh:sbvh", "bvh:sbvh,max_leaf=1", "bvh8,from=sbvh", "bvh4,from=sbvh,leaves=ids",
          "bvh8q,from=sbvh", "bvh16,from=sbvh", "bvh:pair,from=sbvh"}) {
        CAPTURE(slivers, spec);
        const AnyAccel a = build_accel(spec, in);
        REQUIRE(accel_validate(a).empty());
        visit_accel(a, [&](const auto& s) { test::check_agrees_with_brute_force(s, soup, rays); });
    }
}

}  // namespace rtlab
