// Uniform grid: Woo's resolution rule, agreement with brute force on seeded soups (with and
// without a clip callback), rays on cell boundaries, the hit beyond the first cell a primitive
// overlaps, mailboxing, invariants, determinism and traversal counts.

#include "accel/any_accel.h"
#include "accel/brute_force.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {
namespace {

/// The grid built by spec ("grid:uniform" with optional ",key=value" settings).
Grid build_grid(const BuildInput& in, const std::string& spec = "grid:uniform") {
    return std::get<Grid>(build_accel(spec, in));
}

/// Rays starting on cell boundary planes of g: lying in the plane, along it, and crossing it.
std::vector<Rayf> cell_boundary_rays(const Grid& g, std::uint64_t seed, std::size_t count) {
    test::Rng rng(seed);
    std::vector<Rayf> rays;
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t a = rng.below(3);
        Rayf r;
        r.org = rng.point_in(g.box);
        const std::uint32_t k = rng.below(g.res[a] + 1);
        r.org[a] = g.box.lo[a] + static_cast<float>(k) * g.cell_size[a];
        r.dir = rng.direction();
        if (i % 3 == 0) {
            r.dir[a] = 0;  // in the boundary plane
        } else if (i % 3 == 1) {
            r.org[(a + 1) % 3] =
                g.box.lo[(a + 1) % 3] +
                static_cast<float>(rng.below(g.res[(a + 1) % 3] + 1)) * g.cell_size[(a + 1) % 3];
            r.dir = {0, 0, 0};
            r.dir[(a + 2) % 3] = rng.below(2) ? 1.0f : -1.0f;  // along a cell edge line
        }
        rays.push_back(r);
    }
    return rays;
}

}  // namespace

TEST_CASE("grid resolution follows Woo's rule", "[accel][grid]") {
    // Box 2 x 1 x 1, N = 100, lambda = 4: cbrt(400 / 2) = 5.85 cells per unit.
    std::vector<Bounds3f> boxes(100, Bounds3f{{0, 0, 0}, {0.1f, 0.1f, 0.1f}});
    boxes[0] = {{0, 0, 0}, {2, 1, 1}};
    const Grid g = build_grid({boxes, {}});
    CHECK(g.res == std::array<std::uint32_t, 3>{12, 6, 6});
    CHECK(g.cell_start.size() == 12 * 6 * 6 + 1);
    // A flat scene gets one cell across its zero extent and Woo's rule in 2-D over the rest.
    std::vector<Bounds3f> flat(100, Bounds3f{{0, 0, 0}, {1, 1, 0}});
    const Grid f = build_grid({flat, {}});
    CHECK(f.res == std::array<std::uint32_t, 3>{20, 20, 1});
    // The clamp.
    CHECK(build_grid({boxes, {}}, "grid:uniform,max_res=3").res ==
          std::array<std::uint32_t, 3>{3, 3, 3});
}

TEST_CASE("grid agrees with brute force", "[accel][grid]") {
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const float density = GENERATE(0.5f, 4.0f);
    const bool with_clip = GENERATE(false, true);
    const auto count = GENERATE(1u, 2u, 17u, 500u);
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(static_cast<int>(kind), density, with_clip, count, seed);
    const test::Soup soup = test::random_soup(kind, seed, count);
    BuildInput in = soup.input();
    if (with_clip) {
        in.clip = [&soup](std::uint32_t id, const Bounds3f& box) {
            return intersection(soup.boxes[id], box);
        };
    }
    const std::string spec = "grid:uniform,density=" + std::to_string(density);
    const Grid grid = build_grid(in, spec);
    REQUIRE(grid.validate().empty());
    REQUIRE(grid == build_grid(in, spec));
    const AccelInfo info = grid.info();
    CHECK(info.nodes == grid.cell_count());
    CHECK(info.refs_per_prim >= 1.0);

    std::vector<Rayf> rays = test::random_rays(soup, seed, 200);
    const std::vector<Rayf> on_boundaries = cell_boundary_rays(grid, seed, 60);
    rays.insert(rays.end(), on_boundaries.begin(), on_boundaries.end());
    test::check_agrees_with_brute_force(grid, soup, rays);
}

TEST_CASE("uniform grid does not depend on the thread count", "[accel][grid]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 13, 20000);
    BuildInput in = soup.input();
    in.clip = [&soup](std::uint32_t id, const Bounds3f& box) {
        return intersection(soup.boxes[id], box);
    };
    const Grid one = build_grid(in, "grid:uniform,threads=1");
    REQUIRE(one.validate().empty());
    CHECK(one == build_grid(in, "grid:uniform,threads=2"));
    CHECK(one == build_grid(in, "grid:uniform,threads=4"));
    CHECK(one == build_grid(in));
}

TEST_CASE("grid handles primitives and rays on cell boundaries", "[accel][grid]") {
    // Boxes whose faces lie exactly on the cell planes of a 4 x 4 x 4 grid over [0, 4]^3, flat
    // boxes in those planes, duplicates and corner points.
    const test::Soup soup = test::lattice_soup({1, 0, 1});
    const Grid grid = build_grid(soup.input(), "grid:uniform,max_res=4");
    REQUIRE(grid.res == std::array<std::uint32_t, 3>{4, 4, 4});
    REQUIRE(grid.validate().empty());
    test::check_agrees_with_brute_force(grid, soup, cell_boundary_rays(grid, 3, 400));
    test::check_agrees_with_brute_force(grid, soup, test::random_rays(soup, 3, 200));
}

TEST_CASE("grid finds a near hit beyond the first cell of a long primitive", "[accel][grid]") {
    // L: a long slanted triangle spanning every cell the ray crosses, hit at x = 9; S: a small
    // triangle on the ray at x = 5 (nearer) or 9.5 (farther). L is offered in the first cell.
    const float s_x = GENERATE(5.0f, 9.5f);
    CAPTURE(s_x);
    const test::Soup soup = test::long_primitive_soup(s_x);
    const Grid grid = build_grid(soup.input());
    REQUIRE(grid.res[0] > 4);
    const Rayf ray{{-1, 0.5f, 0.5f}, {1, 0, 0}};
    std::vector<std::uint32_t> order;
    Hit h;
    Rayf r = ray;
    const auto record = soup.closest_hit(h);
    TraversalStats st;
    REQUIRE(grid.intersect(
        r,
        [&](std::uint32_t id, Rayf& rr) {
            order.push_back(id);
            return record(id, rr);
        },
        st));
    REQUIRE_FALSE(order.empty());
    CHECK(order.front() == 0u);  // L first, in the first cell, with its hit far beyond it
    if (s_x < 9.0f) {
        CHECK(h.prim == 1u);
        CHECK(h.t == Approx(6.0f));
    } else {
        CHECK(h.prim == 0u);
        CHECK(h.t == Approx(10.0f));
    }
    // Mailboxing: L lies in every cell the ray crosses but is tested once.
    CHECK(std::count(order.begin(), order.end(), 0u) == 1);
    CHECK(st.nodes > 2);
    CHECK(grid.occluded(ray, soup.any_hit()));
}

TEST_CASE("grid of no usable primitive is empty and never hit", "[accel][grid]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<Bounds3f> boxes{Bounds3f{}, {{nan, 0, 0}, {1, 1, 1}}};
    for (const std::size_t n : {std::size_t{0}, std::size_t{2}}) {
        const Grid g = build_grid({std::span(boxes).first(n), {}});
        CHECK(g.validate().empty());
        CHECK(g.cell_count() == 0);
        Rayf r{{-1, 0.5f, 0.5f}, {1, 0, 0}};
        TraversalStats st;
        CHECK_FALSE(g.intersect(
            r, [](std::uint32_t, Rayf&) { return true; }, st));
        CHECK_FALSE(g.occluded(
            r, [](std::uint32_t, const Rayf&) { return true; }, st));
        CHECK(st.nodes == 0);
    }
    // A single point primitive: one cell.
    const std::vector<Bounds3f> point{Bounds3f(Vec3f{1, 2, 3})};
    const Grid p = build_grid({point, {}});
    CHECK(p.res == std::array<std::uint32_t, 3>{1, 1, 1});
    CHECK(p.validate().empty());
}

TEST_CASE("grid rejects invalid rays before touching a cell", "[accel][grid]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 3, 100);
    const Grid grid = build_grid(soup.input());
    test::check_rejects_invalid_rays(grid, soup);
}

TEST_CASE("grid tests far fewer primitives than brute force", "[accel][grid]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 11, 500);
    const std::vector<Rayf> rays = test::random_rays(soup, 11, 400);
    const auto count = [&](const auto& accel) {
        return test::closest_hit_stats(accel, soup, rays);
    };
    const TraversalStats brute = count(BruteForce::build(soup.input()));
    const TraversalStats grid = count(build_grid(soup.input()));
    CHECK(grid.rays == brute.rays);
    CHECK(grid.prims * 5 < brute.nodes);
}

TEST_CASE("grid figures on a 10,000-primitive soup", "[.report][grid]") {
    for (const auto kind : {test::SoupKind::triangles, test::SoupKind::boxes}) {
        const test::Soup soup = test::random_soup(kind, 42, 10000);
        const std::vector<Rayf> rays = test::random_rays(soup, 42, 20000);
        const Grid grid = build_grid(soup.input());
        const TraversalStats st = test::closest_hit_stats(grid, soup, rays);
        const AccelInfo info = grid.info();
        std::printf(
            "grid:uniform %s: nodes/ray %.2f prims/ray %.2f res %ux%ux%u refs/prim %.2f "
            "sah %.2f\n",
            kind == test::SoupKind::boxes ? "boxes" : "triangles",
            static_cast<double>(st.nodes) / static_cast<double>(st.rays),
            static_cast<double>(st.prims) / static_cast<double>(st.rays), grid.res[0], grid.res[1],
            grid.res[2], info.refs_per_prim, info.sah_cost);
        CHECK(grid.validate().empty());
    }
}

}  // namespace rtlab
