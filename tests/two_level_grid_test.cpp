// Two-level grid: agreement with brute force over densities (with and without an exact clip),
// a teapot in a stadium (where it must beat the uniform grid by far), determinism over thread
// counts, invariants and their checker, and empty input.

#include "accel/any_accel.h"
#include "accel/brute_force.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <limits>
#include <string>
#include <vector>

namespace rtlab {
namespace {

TwoLevelGrid build_grid2(const BuildInput& in, const std::string& spec = "grid:two_level") {
    return std::get<TwoLevelGrid>(build_accel(spec, in));
}

/// The exact clip of a box soup: the part of box primitive id inside box is their intersection.
ClipFn box_clip(const test::Soup& soup) {
    return [&soup](std::uint32_t id, const Bounds3f& box) {
        const Bounds3f& b = soup.boxes[id];
        Bounds3f r;
        for (std::size_t a = 0; a < 3; ++a) {
            r.lo[a] = std::max(b.lo[a], box.lo[a]);
            r.hi[a] = std::min(b.hi[a], box.hi[a]);
        }
        return r;
    };
}

/// 2000 small boxes in a cube of side 0.02 at the origin, inside the six walls (flat boxes) of a
/// cube of side 2000: the teapot in a stadium.
test::Soup stadium_soup() {
    test::Soup soup = test::random_soup(test::SoupKind::boxes, 5, 2000);
    for (Bounds3f& b : soup.boxes) {
        if (is_usable_box(b)) {
            b = {b.lo * 0.02f, b.hi * 0.02f};
        }
    }
    for (std::size_t a = 0; a < 3; ++a) {
        for (const float side : {-1000.0f, 1000.0f}) {
            Bounds3f wall{{-1000, -1000, -1000}, {1000, 1000, 1000}};
            wall.lo[a] = wall.hi[a] = side;
            soup.boxes.push_back(wall);
        }
    }
    return soup;
}

}  // namespace

TEST_CASE("two-level grid agrees with brute force", "[accel][grid2]") {
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const auto top = GENERATE(0.01, 0.0625, 1.0);
    const auto leaf = GENERATE(0.5, 2.0, 8.0);
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(static_cast<int>(kind), top, leaf, seed);
    const test::Soup soup = test::random_soup(kind, seed, 700);
    const std::string spec = "grid:two_level,top_density=" + std::to_string(top) +
                             ",leaf_density=" + std::to_string(leaf);
    const TwoLevelGrid g = build_grid2(soup.input(), spec);
    REQUIRE(g.validate().empty());
    test::check_agrees_with_brute_force(g, soup, test::random_rays(soup, seed, 300));
    if (kind == test::SoupKind::boxes) {
        // The exact clip of a box is its overlap with the cell, which the builder also uses
        // without a clip: the same structure either way.
        const TwoLevelGrid clipped = build_grid2({soup.boxes, box_clip(soup)}, spec);
        REQUIRE(clipped.validate().empty());
        CHECK(clipped == g);
        test::check_agrees_with_brute_force(clipped, soup, test::random_rays(soup, seed + 1, 300));
    }
}

TEST_CASE("two-level grid survives the stadium", "[accel][grid2]") {
    const test::Soup soup = stadium_soup();
    const TwoLevelGrid g2 = build_grid2({soup.boxes, box_clip(soup)});
    const Grid g1 = std::get<Grid>(build_accel("grid:uniform", {soup.boxes, box_clip(soup)}));
    REQUIRE(g2.validate().empty());
    // Rays from the stadium's inside aimed at the small object, and random ones.
    test::Rng rng(17);
    std::vector<Rayf> rays;
    for (int i = 0; i < 300; ++i) {
        const Vec3f org{rng.uniform(-900, 900), rng.uniform(-900, 900), rng.uniform(-900, 900)};
        const Vec3f target = rng.point_in({{0, 0, 0}, {0.02f, 0.02f, 0.02f}});
        rays.push_back({org, normalize(target - org)});
    }
    test::check_agrees_with_brute_force(g2, soup, rays);
    test::check_agrees_with_brute_force(g2, soup, test::random_rays(soup, 17, 300));
    const TraversalStats s1 = test::closest_hit_stats(g1, soup, rays);
    const TraversalStats s2 = test::closest_hit_stats(g2, soup, rays);
    CAPTURE(s1.prims, s2.prims, s1.nodes, s2.nodes);
    // The uniform grid's cells are stretched by the walls: the object lands in one or a few
    // cells, each ray tests a large share of its 2000 boxes; the sub-grid has small cells.
    CHECK(s2.prims * 5 <= s1.prims);
}

TEST_CASE("two-level grid does not depend on the thread count", "[accel][grid2]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 9, 3000);
    const TwoLevelGrid one = build_grid2(soup.input(), "grid:two_level,threads=1");
    const TwoLevelGrid two = build_grid2(soup.input(), "grid:two_level,threads=2");
    const TwoLevelGrid all = build_grid2(soup.input());
    CHECK(one == two);
    CHECK(one == all);
    CHECK(one.subs.size() > 1);
}

TEST_CASE("two-level grid invariants are checked", "[accel][grid2]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 4, 300);
    const TwoLevelGrid good = build_grid2(soup.input());
    REQUIRE(good.validate().empty());
    const AccelInfo info = good.info();
    CHECK(info.nodes == good.top_sub.size() + good.cell_start.size() - 1);
    CHECK(info.refs_per_prim >= 1.0);
    CHECK(info.max_depth == 1);
    {
        TwoLevelGrid b = good;
        b.cell_prims.back() = static_cast<std::uint32_t>(soup.boxes.size());
        CHECK_FALSE(b.validate().empty());
    }
    {
        TwoLevelGrid b = good;
        b.cell_start[1] = b.cell_start.back() + 1;
        CHECK_FALSE(b.validate().empty());
    }
    {
        TwoLevelGrid b = good;
        b.subs.front().first_cell += 1;
        CHECK_FALSE(b.validate().empty());
    }
    {
        TwoLevelGrid b = good;
        b.subs.front().frame.box.lo.x = good.top.box.lo.x - 1;
        CHECK_FALSE(b.validate().empty());
    }
    {
        TwoLevelGrid b = good;  // every reference names one primitive: the others are lost
        b.cell_prims.assign(b.cell_prims.size(), b.cell_prims.front());
        CHECK_FALSE(b.validate().empty());
    }
}

TEST_CASE("two-level grid of no usable primitive is empty; invalid rays are rejected",
          "[accel][grid2]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<Bounds3f> boxes{Bounds3f{}, {{nan, 0, 0}, {1, 1, 1}}};
    const TwoLevelGrid g = build_grid2({boxes, {}});
    CHECK(g.validate().empty());
    CHECK(g.top_sub.empty());
    TraversalStats st;
    Rayf r{{-1, 0.5f, 0.5f}, {1, 0, 0}};
    CHECK_FALSE(g.intersect(
        r, [](std::uint32_t, Rayf&) { return true; }, st));
    CHECK(st.nodes == 0);
    const std::vector<Bounds3f> point{Bounds3f(Vec3f{1, 2, 3})};
    const TwoLevelGrid p = build_grid2({point, {}});
    CHECK(p.validate().empty());
    CHECK(p.subs.size() == 1);
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 3, 100);
    test::check_rejects_invalid_rays(build_grid2(soup.input()), soup);
}

}  // namespace rtlab
