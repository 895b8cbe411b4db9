// The pair layout (bvh:pair): the source tree kept, pushed children skipped behind a nearer hit,
// the larger child first.

#include "accel/any_accel.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "support/bvh_checks.h"
#include "support/registry_lists.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtlab {

TEST_CASE("pair layout keeps the source tree: leaves, boxes and answers", "[accel][bvh]") {
    const std::string from = GENERATE(from_range(test::from_choices()));
    const auto count = GENERATE(0u, 1u, 2u, 5u, 1000u);
    CAPTURE(from, count);
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 3, count);
    // The source's settings (max_leaf 4, Ct 1, 16 bins), not the pair row's defaults; leaves
    // packed as the source's (the default aligns them: align_leaf_slots, tested below).
    const std::string_view settings = "max_leaf=4,ct=1,bins=16,block=1";
    const Bvh source =
        std::get<Bvh>(build_accel(test::spec_with("bvh:" + from, settings), soup.input()));
    const AnyAccel any = build_accel(
        test::spec_with("bvh:pair", "from=" + from + "," + std::string(settings) + ",leaf_align=1"),
        soup.input());
    const PairBvh& pair = std::get<PairBvh>(any);
    REQUIRE(pair.validate().empty());
    CHECK(pair == PairBvh::convert(source));
    CHECK(pair.prim_ids == source.prim_ids);
    CHECK(pair.bounds() == source.bounds());
    const AccelInfo pi = pair.info(), si = source.info();
    CHECK(pi.leaves == si.leaves);
    CHECK(pi.max_depth == si.max_depth);
    CHECK(pi.sah_cost == Approx(si.sah_cost).epsilon(1e-12));  // summed in another order
    CHECK(source.nodes.size() == (count == 0 ? 0 : 2 * pi.nodes + 1));
    // Same leaves, same primitive tests: the closest hit's t is the same on every ray.
    for (const Rayf& ray : test::random_rays(soup, 3, 200)) {
        Hit a, b;
        Rayf ra = ray, rb = ray;
        const bool ha = source.intersect(ra, soup.closest_hit(a));
        const bool hb = pair.intersect(rb, soup.closest_hit(b));
        CHECK(ha == hb);
        CHECK(a.t == b.t);
        CHECK(source.occluded(ray, soup.any_hit()) == pair.occluded(ray, soup.any_hit()));
    }
}

TEST_CASE("pair layout skips a pushed child once a nearer hit closes the window", "[accel][bvh]") {
    // Two unit boxes along +x at x in [0,1] and [3,4]; a ray from x = -1 hits the first box's
    // primitive at t = 1, so the farther leaf (entry t = 4) is never tested.
    const std::vector<Bounds3f> boxes{{{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {4, 1, 1}}};
    const PairBvh pair = PairBvh::convert(test::build_with(boxes, "bvh:binned", 1));
    REQUIRE(pair.nodes.size() == 1);
    Rayf ray{{-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 100};
    std::vector<std::uint32_t> tested;
    TraversalStats st;
    const bool hit = pair.intersect(
        ray,
        [&](std::uint32_t id, Rayf& r) {
            tested.push_back(id);
            r.tmax = std::min(r.tmax, boxes[id].lo.x + 1.0f);  // hits at the box's near face
            return true;
        },
        st);
    CHECK(hit);
    CHECK(tested == std::vector<std::uint32_t>{0});
    CHECK(st.nodes == 3);  // the root box, then both children at once
}

TEST_CASE("pair layout puts the larger child first and descends on the ray's side of the split",
          "[accel][bvh]") {
    // A unit box at x in [0, 1] and a larger one at x in [3, 5]: split on x, the larger (the
    // source's upper child) becomes child 0.
    const std::vector<Bounds3f> boxes{{{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {5, 1, 1}}};
    const Bvh source = test::build_with(boxes, "bvh:binned", 1);
    const PairBvh pair = PairBvh::convert(source);
    REQUIRE(pair.nodes.size() == 1);
    const PairNode& n = pair.nodes[0];
    CHECK(n.axis() == 0);
    CHECK(n.flipped() == 1);
    CHECK(n.child_bounds(0) == boxes[1]);
    CHECK(n.count_of(0) == 1);
    CHECK(n.count_of(1) == 1);
    const PairBvh kept = PairBvh::convert(source, ChildOrder::build);
    CHECK(kept.nodes[0].flipped() == 0);
    CHECK(kept.nodes[0].child_bounds(0) == boxes[0]);
    const auto order_tested = [&](Rayf ray, bool any) {
        std::vector<std::uint32_t> tested;
        if (any) {
            pair.occluded(ray, [&](std::uint32_t id, const Rayf&) {
                tested.push_back(id);
                return false;  // no blocker: every hit box's primitive is offered
            });
        } else {
            pair.intersect(ray, [&](std::uint32_t id, Rayf&) {
                tested.push_back(id);
                return false;
            });
        }
        return tested;
    };
    using Ids = std::vector<std::uint32_t>;
    // Closest hit: the ray's side of the split first, whichever child holds it.
    CHECK(order_tested({{-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 100}, false) == Ids{0, 1});
    CHECK(order_tested({{6, 0.5f, 0.5f}, {-1, 0, 0}, 0, 100}, false) == Ids{1, 0});
    // Any hit: child 0, the larger box, first.
    CHECK(order_tested({{-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 100}, true) == Ids{1, 0});
}

}  // namespace rtlab
