// Binary BVH builders across thread counts and node-box orders, the radix sort of their keys and
// the full-sweep SAH split.

#include "accel/any_accel.h"
#include "accel/bvh/build_common.h"
#include "support/accel_fixtures.h"
#include "support/bvh_checks.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {

TEST_CASE("parallel binned SAH builds the same tree for 1, 2 and 4 threads", "[accel][bvh]") {
    // 70000 primitives: above the builder's thresholds for parallel binning and partitioning
    // (65536) and for subtree tasks (4096), so every parallel path runs.
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    CAPTURE(static_cast<int>(kind));
    const test::Soup soup = test::random_soup(kind, 5, 70000);
    const Bvh one = test::build_with(soup.boxes, "bvh:pbinned", 4, ",threads=1");
    test::check_layout(one, soup.boxes);
    for (const int threads : {2, 4}) {
        CAPTURE(threads);
        CHECK(one == test::build_with(soup.boxes, "bvh:pbinned", 4,
                                      ",threads=" + std::to_string(threads)));
    }
    CHECK(one == test::build_with(soup.boxes, "bvh:pbinned", 4, ",threads=0"));
    // The same SAH quality as the sequential binned builder, within a few percent.
    const double par = one.info().sah_cost;
    const double seq = test::build_with(soup.boxes, "bvh:binned").info().sah_cost;
    CAPTURE(par, seq);
    CHECK(par <= seq * 1.05);
}

TEST_CASE("top-down BVH builders build the same tree for 1, 2 and 4 threads", "[accel][bvh]") {
    // 70000 primitives: nodes above TopDown::parallel_min (4096) build their children as tasks
    // (each subtree below it densely into its own array, placed after; one thread appends into
    // one array), and box unions over 65536 or more primitives are reduced in parallel blocks.
    const std::string row =
        GENERATE(as<std::string>{}, "bvh:median", "bvh:binned", "bvh:sweep", "bvh:lbvh");
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    CAPTURE(row, static_cast<int>(kind));
    // Empty boxes spread over every block of the parallel collection of usable ids.
    std::vector<Bounds3f> boxes = test::random_soup(kind, 31, 70000).boxes;
    for (std::size_t i = 0; i < boxes.size(); i += 997) {
        boxes[i] = Bounds3f{};
    }
    const Bvh one = test::build_with(boxes, row, 4, ",threads=1");
    test::check_layout(one, boxes);
    CHECK(one.unreferenced_count == (boxes.size() + 996) / 997);
    for (const int threads : {2, 4, 0}) {
        CAPTURE(threads);
        const Bvh many = test::build_with(boxes, row, 4, ",threads=" + std::to_string(threads));
        test::check_layout(many, boxes);
        CHECK(one == many);
    }
}

TEST_CASE("TopDown gives the same tree with node boxes before or after the split", "[accel][bvh]") {
    // bvh:lbvh and bvh:median fill boxes in bottom-up (NodeBoxes::after_split); the SAH rows
    // compute them top-down for their costs. min / max are exact, so the trees must match.
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const bool parallel = GENERATE(false, true);
    CAPTURE(static_cast<int>(kind), parallel);
    const std::vector<Bounds3f> boxes = test::random_soup(kind, 17, 70000).boxes;
    Bvh::Config cfg;
    cfg.max_leaf_size = 4;
    const auto split = bvh_detail::TopDown::median_or_leaf;
    const BuildInput in{boxes, {}};
    const Bvh before = bvh_detail::TopDown(in, bvh_detail::clamped(cfg)).run(split, parallel);
    const Bvh after = bvh_detail::TopDown(in, bvh_detail::clamped(cfg))
                          .run<bvh_detail::NodeBoxes::after_split>(split, parallel);
    test::check_layout(before, boxes);
    REQUIRE(before.nodes.size() > 1000);
    CHECK(before == after);
}

TEST_CASE("sort keys order floats as they compare; the radix sort is a stable sort on them",
          "[accel][bvh]") {
    // The full-sweep builder sorts centres as float_order_key(centre) << 32 | id.
    constexpr float inf = std::numeric_limits<float>::infinity();
    const float ascending[] = {-inf,
                               -std::numeric_limits<float>::max(),
                               -1.5f,
                               -1.0f,
                               -std::numeric_limits<float>::denorm_min(),
                               0.0f,
                               std::numeric_limits<float>::denorm_min(),
                               1.0f,
                               1.5f,
                               std::numeric_limits<float>::max(),
                               inf};
    for (std::size_t i = 0; i + 1 < std::size(ascending); ++i) {
        CAPTURE(ascending[i], ascending[i + 1]);
        CHECK(bvh_detail::float_order_key(ascending[i]) <
              bvh_detail::float_order_key(ascending[i + 1]));
    }
    CHECK(bvh_detail::float_order_key(-0.0f) == bvh_detail::float_order_key(0.0f));
    // 200,000 keys (several 65536-key blocks: the most significant digit first, then each bucket)
    // and 50,000 (LSD passes only), codes from few values so that ties are common, ids in
    // increasing order: the radix sort on the high 32 bits (3 digits of 11 bits), on 30 of them
    // (3 of 10) and on 7 (one pass) equals std::stable_sort on those bits.
    const std::uint32_t bits = GENERATE(32u, 30u, 7u);
    const std::size_t count = GENERATE(200000u, 50000u);
    CAPTURE(bits, count);
    test::Rng rng(bits);
    ScratchVector<std::uint64_t> keys(count);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const float f = static_cast<float>(static_cast<int>(rng.below(2001)) - 1000) * 0.25f;
        std::uint32_t code = bvh_detail::float_order_key(f);
        if (bits < 32) {
            code = static_cast<std::uint32_t>(rng.next()) & ((1u << bits) - 1);
        }
        keys[i] = (std::uint64_t{code} << 32) | i;
    }
    std::vector<std::uint64_t> expected(keys.begin(), keys.end());
    std::stable_sort(expected.begin(), expected.end(),
                     [](std::uint64_t x, std::uint64_t y) { return (x >> 32) < (y >> 32); });
    bvh_detail::radix_sort_by_high(keys, bits);
    CHECK(std::equal(keys.begin(), keys.end(), expected.begin(), expected.end()));
}

TEST_CASE("full-sweep SAH splits the root where the serial sweep's minimum is", "[accel][bvh]") {
    // 70000 primitives: the root's sweeps run in parallel blocks (65536 or more), each from the
    // unions of the blocks beside it. The split's cost must be the minimum over every split
    // between consecutive centres (ties by id) on every axis, computed here one slot at a time.
    // Shifted, the centres straddle 0 and every 50th box is flat at x = -0 or +0 (equal centres,
    // so ordered by id): the sort's keys must order floats as floats compare.
    const bool shifted = GENERATE(false, true);
    CAPTURE(shifted);
    std::vector<Bounds3f> boxes = test::random_soup(test::SoupKind::triangles, 7, 70000).boxes;
    for (std::size_t i = 0; shifted && i < boxes.size(); ++i) {
        const Vec3f shift{-0.5f, -0.5f, -0.5f};
        boxes[i] = {boxes[i].lo + shift, boxes[i].hi + shift};
        if (i % 50 == 0) {
            boxes[i].lo.x = boxes[i].hi.x = i % 100 == 0 ? -0.0f : 0.0f;
        }
    }
    const Bvh bvh = test::build_with(boxes, "bvh:sweep");
    const BvhNode& root = bvh.nodes.at(0);
    REQUIRE_FALSE(root.is_leaf());
    const auto prims_under = [&](std::uint32_t node) {
        std::uint32_t count = 0;
        std::vector<std::uint32_t> todo{node};
        while (!todo.empty()) {
            const BvhNode& n = bvh.nodes[todo.back()];
            todo.pop_back();
            if (n.is_leaf()) {
                count += n.prim_count();
            } else {
                todo.insert(todo.end(), {n.first, n.first + 1});
            }
        }
        return count;
    };
    const BvhNode& left = bvh.nodes[root.first];
    const BvhNode& right = bvh.nodes[root.first + 1];
    const float built =
        left.bounds().surface_area() * static_cast<float>(prims_under(root.first)) +
        right.bounds().surface_area() * static_cast<float>(prims_under(root.first + 1));

    float best = std::numeric_limits<float>::infinity();
    const std::size_t n = boxes.size();
    for (std::size_t a = 0; a < 3; ++a) {
        std::vector<std::uint32_t> order(n);
        for (std::uint32_t i = 0; i < n; ++i) {
            order[i] = i;
        }
        std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
            const float cx = boxes[x].center()[a], cy = boxes[y].center()[a];
            return cx < cy || (cx == cy && x < y);
        });
        std::vector<float> right_area(n);
        Bounds3f acc;
        for (std::size_t i = n; i-- > 1;) {
            acc.extend(boxes[order[i]]);
            right_area[i] = acc.surface_area();
        }
        acc = Bounds3f{};
        for (std::size_t i = 1; i < n; ++i) {
            acc.extend(boxes[order[i - 1]]);
            best = std::min(best, acc.surface_area() * static_cast<float>(i) +
                                      right_area[i] * static_cast<float>(n - i));
        }
    }
    CHECK(built == best);
}
}  // namespace rtlab
