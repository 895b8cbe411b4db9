// BVH node layout, tree invariants and builder-specific edge cases (across thread counts, the
// radix sort and the full sweep: bvh_build_test.cpp; the pair layout: bvh_pair_test.cpp).

#include "accel/any_accel.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "support/bvh_checks.h"

#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rtlab {
namespace {

/// The names of every registry row that builds a binary Bvh (builders, not converted layouts),
/// in registry order.
std::vector<std::string> bvh_rows() {
    std::vector<std::string> out;
    for (const AccelEntry& e : accel_registry()) {
        if (std::holds_alternative<Bvh>(e.build(BuildInput{}, default_spec(e)))) {
            out.emplace_back(e.name);
        }
    }
    return out;
}

}  // namespace

TEST_CASE("BvhNode keeps Wald's 32-byte layout", "[accel][bvh]") {
    STATIC_REQUIRE(sizeof(BvhNode) == 32);
    STATIC_REQUIRE(alignof(BvhNode) == 32);
    const Bounds3f box{{0, 1, 2}, {3, 4, 5}};
    const BvhNode leaf = BvhNode::make_leaf(box, 7, BvhNode::max_prim_count);
    CHECK(leaf.is_leaf());
    CHECK(leaf.first == 7);
    CHECK(leaf.prim_count() == BvhNode::max_prim_count);
    CHECK(leaf.bounds() == box);
    const BvhNode inner = BvhNode::make_inner(box, 9, 2);
    CHECK_FALSE(inner.is_leaf());
    CHECK(inner.first == 9);
    CHECK(inner.axis() == 2);
    CHECK(inner.prim_count() == 0);
}

TEST_CASE("every builder gives a valid, tight, deterministic tree", "[accel][bvh]") {
    const std::string builder = GENERATE(from_range(bvh_rows()));
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const auto count = GENERATE(0u, 1u, 2u, 3u, 17u, 1000u);
    const auto max_leaf = GENERATE(1u, 4u, 8u);
    CAPTURE(builder, static_cast<int>(kind), count, max_leaf);
    const test::Soup soup = test::random_soup(kind, 42, count);
    const Bvh bvh = test::build_with(soup.boxes, builder, max_leaf);
    test::check_layout(bvh, soup.boxes, builder == "bvh:sbvh");
    CHECK(bvh == test::build_with(soup.boxes, builder, max_leaf));
    CHECK(bvh.prim_count == count);
    const AccelInfo info = bvh.info();
    CHECK(info.nodes == bvh.nodes.size());
    CHECK(info.leaves == (bvh.nodes.size() + 1) / 2);
    CHECK(info.bytes == bvh.nodes.size() * 32 + bvh.prim_ids.size() * 4);
    // Object splits reference each usable primitive exactly once; spatial splits may cut one.
    CHECK((builder == "bvh:sbvh" || bvh.prim_ids.empty() || info.refs_per_prim == 1.0));
    if (count == 0) {
        CHECK(bvh.nodes.empty());
        CHECK(bvh.bounds().empty());
    } else {
        CHECK(bvh.bounds() == soup.scene_bounds());
        CHECK(info.sah_cost >= 1.0);  // at least the root's own cost
    }
}

TEST_CASE("SAH builders beat the median and LBVH trees on the SAH metric", "[accel][bvh]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 9, 2000);
    const double median = test::build_with(soup.boxes, "bvh:median").info().sah_cost;
    // All four measured with the same costs (Ct 1, Ci 1: the median and LBVH rows' Config).
    const double binned = test::build_with(soup.boxes, "bvh:binned", 4, ",ct=1").info().sah_cost;
    const double sweep = test::build_with(soup.boxes, "bvh:sweep", 4, ",ct=1").info().sah_cost;
    const double lbvh = test::build_with(soup.boxes, "bvh:lbvh").info().sah_cost;
    CAPTURE(median, binned, sweep, lbvh);
    CHECK(sweep <= binned * 1.02);
    CHECK(binned < median);
    CHECK(sweep < lbvh);
}

TEST_CASE("SAH builders leave no range a leaf beats whatever its split", "[accel][bvh]") {
    // A range of n <= max_leaf with Ci * n <= Ct costs at most Ct * A as a leaf, which no split's
    // Ct * A + Ci * (A_L n_L + A_R n_R) undercuts: no inner node holds that few primitives. With
    // blocks of k, n counts ceil(n / k) on both sides.
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 11, 2000);
    const std::string row = GENERATE("bvh:pbinned", "bvh:binned", "bvh:sweep");
    const auto [costs, most] =
        GENERATE(std::pair<std::string, std::uint32_t>{",ct=4,block=1", 4},
                 std::pair<std::string, std::uint32_t>{",ct=3,block=1", 3},
                 std::pair<std::string, std::uint32_t>{",ct=2,ci=0.5,block=1", 4},
                 std::pair<std::string, std::uint32_t>{",ct=2,block=4", 8},
                 std::pair<std::string, std::uint32_t>{",ct=1,block=3", 3});
    CAPTURE(row, costs);
    const Bvh bvh = test::build_with(soup.boxes, row, 8, costs);
    test::check_layout(bvh, soup.boxes);
    // Children are stored after their parent, so one backward pass sums subtree sizes.
    std::vector<std::uint32_t> size(bvh.nodes.size());
    std::size_t inner = 0, small_inner = 0;
    for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
        const BvhNode& n = bvh.nodes[i];
        if (n.is_leaf()) {
            size[i] = n.prim_count();
            continue;
        }
        size[i] = size[n.first] + size[n.first + 1];
        ++inner;
        small_inner += size[i] <= most ? 1 : 0;
    }
    CHECK(inner > 100);
    CHECK(small_inner == 0);
}

TEST_CASE("binned SAH handles one and two bins", "[accel][bvh]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 5, 300);
    const auto bins = GENERATE(1u, 2u, 3u, 64u);
    CAPTURE(bins);
    const Bvh bvh = test::build_with(soup.boxes, "bvh:binned", 4, ",bins=" + std::to_string(bins));
    test::check_layout(bvh, soup.boxes);
    CHECK(bvh.config.bin_count == bins);
    if (bins <= 1) {
        // One bin has no split candidate: the builder falls back to the object median.
        CHECK(bvh.nodes == test::build_with(soup.boxes, "bvh:median").nodes);
    }
}

TEST_CASE("builders split equal centroids and duplicates by count", "[accel][bvh]") {
    const std::string builder = GENERATE(from_range(bvh_rows()));
    CAPTURE(builder);
    // 100 boxes with one centre: 50 identical, 50 of growing size.
    std::vector<Bounds3f> boxes;
    for (int i = 0; i < 100; ++i) {
        const float h = i < 50 ? 0.25f : 0.01f * static_cast<float>(i);
        boxes.push_back({{0.5f - h, 0.5f - h, 0.5f - h}, {0.5f + h, 0.5f + h, 0.5f + h}});
    }
    const Bvh bvh = test::build_with(boxes, builder, 3);
    test::check_layout(bvh, boxes);
    CHECK(bvh.info().max_depth <= 7);  // balanced: ceil(log2(100 / 3)) = 6 levels of splits
}

TEST_CASE("LBVH codes: bit interleaving and duplicate codes", "[accel][bvh]") {
    // Points on a 4 x 4 x 4 lattice, each twice: Morton order groups the duplicates, and with 2
    // bits per axis every code is distinct across lattice points.
    std::vector<Bounds3f> boxes;
    for (int i = 0; i < 64; ++i) {
        const Vec3f p{static_cast<float>(i % 4), static_cast<float>(i / 4 % 4),
                      static_cast<float>(i / 16)};
        boxes.emplace_back(p);
        boxes.emplace_back(p);
    }
    const Bvh bvh = test::build_with(boxes, "bvh:lbvh", 2, ",morton_bits=2");
    test::check_layout(bvh, boxes);
    // The radix tree over 64 distinct codes is complete: 6 levels above the duplicate pairs.
    CHECK(bvh.info().max_depth == 6);
    CHECK(bvh.info().leaves == 64);
    for (const BvhNode& n : bvh.nodes) {
        if (n.is_leaf()) {
            CHECK(n.prim_count() == 2);
            CHECK(n.lo == n.hi);  // both primitives at the same lattice point
        }
    }
    // The root splits on the top code bit, which is x's highest bit.
    CHECK(bvh.nodes[0].axis() == 0);
}

TEST_CASE("LBVH orders primitives by Morton code, ties by id, across radix blocks",
          "[accel][bvh]") {
    // 70,000 points on the 4x4x4 lattice in random order: with morton_bits=2 each coordinate's
    // cell is the coordinate itself, so the expected order is (code, id) sorted here with
    // std::sort. More keys than one radix-sort block (65,536) and long runs of equal codes.
    std::mt19937 rng(5);
    std::vector<Bounds3f> boxes;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expect;
    for (std::uint32_t i = 0; i < 70000; ++i) {
        // The first 64 cover the lattice, so the centroid bounds are [0, 3] on every axis.
        const std::uint32_t cell = i < 64 ? i : static_cast<std::uint32_t>(rng() % 64);
        const std::uint32_t x = cell % 4, y = cell / 4 % 4, z = cell / 16;
        std::uint32_t code = 0;
        for (std::uint32_t bit = 0; bit < 2; ++bit) {
            code |= ((x >> bit & 1u) << (3 * bit + 2)) | ((y >> bit & 1u) << (3 * bit + 1)) |
                    ((z >> bit & 1u) << (3 * bit));
        }
        boxes.emplace_back(
            Vec3f{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
        expect.emplace_back(code, i);
    }
    std::sort(expect.begin(), expect.end());
    for (const int threads : {1, 2}) {
        CAPTURE(threads);
        const Bvh bvh = test::build_with(boxes, "bvh:lbvh", 4,
                                         ",morton_bits=2,threads=" + std::to_string(threads));
        test::check_layout(bvh, boxes);
        REQUIRE(bvh.prim_ids.size() == expect.size());
        std::size_t out_of_order = 0;
        for (std::size_t i = 0; i < expect.size(); ++i) {
            out_of_order += bvh.prim_ids[i] == expect[i].second ? 0 : 1;
        }
        CHECK(out_of_order == 0);
    }
}

TEST_CASE("depth stays within 64 on exponentially spaced primitives", "[accel][bvh]") {
    // Centres at 1.4^i: every SAH split peels off the largest box, which would nest 300 levels
    // deep without the depth guard.
    const std::string builder = GENERATE(from_range(bvh_rows()));
    CAPTURE(builder);
    std::vector<Bounds3f> boxes;
    float x = 1.0f;
    for (int i = 0; i < 250; ++i) {
        boxes.push_back({{x, 0, 0}, {x * 1.2f, 1, 1}});
        x *= 1.4f;
    }
    const Bvh bvh = test::build_with(boxes, builder, 1);
    test::check_layout(bvh, boxes);
    CHECK(bvh.info().max_depth <= 64);
}

TEST_CASE("empty, NaN and infinite boxes are never referenced", "[accel][bvh]") {
    const std::string builder = GENERATE(from_range(bvh_rows()));
    CAPTURE(builder);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<Bounds3f> boxes{Bounds3f{},
                                {{nan, 0, 0}, {1, 1, 1}},
                                {{0, 0, 0}, {1, 1, 1}},
                                {{-inf, 0, 0}, {1, 1, 1}},
                                {{2, 0, 0}, {1, 1, 1}},
                                {{0, 0, 0}, {0, 0, 0}}};
    const Bvh bvh = test::build_with(boxes, builder, 1);
    test::check_layout(bvh, boxes);
    CHECK(bvh.prim_ids.size() == 2);
    CHECK(bvh.unreferenced_count == 4);
    const Bvh none = test::build_with({Bounds3f{}, Bounds3f{}}, builder);
    CHECK(none.nodes.empty());
    CHECK(none.validate().empty());
    Rayf r{{-1, 0.5f, 0.5f}, {1, 0, 0}};
    CHECK_FALSE(none.intersect(r, [](std::uint32_t, Rayf&) { return true; }));
}

TEST_CASE("validate reports broken trees", "[accel][bvh]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 8, 50);
    const Bvh good = test::build_with(soup.boxes, "bvh:sweep");
    REQUIRE(good.validate().empty());
    Bvh b = good;
    b.prim_ids[0] = b.prim_ids[1];
    CHECK_FALSE(b.validate().empty());
    b = good;
    b.nodes[1].hi.x += 10;  // child outside parent
    CHECK_FALSE(b.validate().empty());
    b = good;
    b.config.max_leaf_size = 1;  // leaves now too big
    CHECK_FALSE(b.validate().empty());
    b = good;
    b.nodes[0].first = 0;  // cycle
    CHECK_FALSE(b.validate().empty());
    // A primitive may sit in several leaves (spatial splits), never twice in one.
    const Bounds3f box{{0, 0, 0}, {1, 1, 1}};
    Bvh shared;
    shared.prim_count = 2;
    shared.config.max_leaf_size = 4;
    shared.prim_ids = {0, 1, 1};
    shared.nodes.push_back(BvhNode::make_inner(box, 1, 0));
    shared.nodes.push_back(BvhNode::make_leaf(box, 0, 2));
    shared.nodes.push_back(BvhNode::make_leaf(box, 2, 1));
    CHECK(shared.validate().empty());
    CHECK(shared.info().refs_per_prim == 1.5);
    shared.prim_ids = {0, 0, 1};
    CHECK(shared.validate().find("twice in one leaf") != std::string::npos);
    // Aligned leaves: a leaf moved one slot back over the padding before it holds a padding slot
    // and leaves its last slot in no leaf.
    const Bvh aligned = align_leaf_slots(good, 4);
    REQUIRE(aligned.validate().empty());
    REQUIRE(aligned.prim_ids.size() > good.prim_ids.size());
    b = aligned;
    for (BvhNode& n : b.nodes) {
        if (n.is_leaf() && n.first > 0 && b.prim_ids[n.first - 1] == padding_slot) {
            --n.first;
            break;
        }
    }
    CHECK(b.validate().find("padding slot") != std::string::npos);
    b = aligned;
    b.prim_ids.push_back(b.prim_ids[0]);
    CHECK_FALSE(b.validate().empty());
}

TEST_CASE("aligned leaf slots keep the tree, its leaves' order and its answers", "[accel][bvh]") {
    // 70,000: the parallel passes split into several blocks.
    const auto count = GENERATE(0u, 1u, 5u, 1000u, 70000u);
    const auto k = GENERATE(1u, 2u, 4u, 8u);
    CAPTURE(count, k);
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 5, count);
    const Bvh source = test::build_with(soup.boxes, "bvh:binned");
    const Bvh a = align_leaf_slots(source, k);
    REQUIRE(a.validate().empty());
    REQUIRE(a.nodes.size() == source.nodes.size());
    std::size_t leaves = 0;
    std::vector<std::uint32_t> order_aligned;  // the ids in slot order, padding left out
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        const BvhNode &n = a.nodes[i], &s = source.nodes[i];
        CHECK(n.bounds() == s.bounds());
        CHECK(n.packed == s.packed);
        if (!n.is_leaf()) {
            CHECK(n.first == s.first);
            continue;
        }
        ++leaves;
        CHECK(n.first % k == 0);
        for (std::uint32_t j = 0; j < n.prim_count(); ++j) {
            CHECK(a.prim_ids[n.first + j] == source.prim_ids[s.first + j]);
        }
    }
    for (const std::uint32_t id : a.prim_ids) {
        if (id != padding_slot) {
            order_aligned.push_back(id);
        }
    }
    CHECK(order_aligned == source.prim_ids);
    CHECK(a.prim_ids.size() <= source.prim_ids.size() + (k - 1) * leaves);
    for (const Rayf& ray : test::random_rays(soup, 5, 200)) {
        Hit x, y;
        Rayf rx = ray, ry = ray;
        CHECK(source.intersect(rx, soup.closest_hit(x)) == a.intersect(ry, soup.closest_hit(y)));
        CHECK(x.t == y.t);
        CHECK(x.prim == y.prim);
        CHECK(source.occluded(ray, soup.any_hit()) == a.occluded(ray, soup.any_hit()));
    }
}

TEST_CASE("closest-hit traversal visits the near child first", "[accel][bvh]") {
    // Two separated boxes on x: a ray along +x opens the left leaf first and, having hit it,
    // culls the right one; along -x the other way round.
    const std::vector<Bounds3f> boxes{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 1}}};
    const Bvh bvh = test::build_with(boxes, "bvh:sweep", 1);
    test::Soup soup;
    soup.boxes = boxes;
    for (const float sign : {1.0f, -1.0f}) {
        Rayf r{{sign > 0 ? -1.0f : 4.0f, 0.5f, 0.5f}, {sign, 0, 0}};
        Hit h;
        TraversalStats st;
        CHECK(bvh.intersect(r, soup.closest_hit(h), st));
        CHECK(h.prim == (sign > 0 ? 0u : 1u));
        CHECK(st.prims == 1);
        CHECK(st.nodes == 3);  // root, near leaf, far leaf culled by the shrunk window
    }
}

TEST_CASE("info() reports the analytic SAH cost of a two-leaf tree", "[accel][bvh]") {
    // Root [0,3]x[0,1]x[0,1] has area 14, each unit-cube leaf area 6: cost = Ct + Ci * 12 / 14.
    const std::string builder = GENERATE(from_range(bvh_rows()));
    CAPTURE(builder);
    const std::vector<Bounds3f> boxes{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 1}}};
    // Rows without cost parameters (the builder ignores them) report with Ct = Ci = 1.
    const bool has_costs = test::declares(*find_accel(builder), "ct");
    const Bvh bvh = test::build_with(boxes, builder, 1, has_costs ? ",ct=2,ci=3" : "");
    const double ct = static_cast<double>(bvh.config.traversal_cost);
    const double ci = static_cast<double>(bvh.config.intersection_cost);
    CHECK(ct == (has_costs ? 2.0 : 1.0));
    CHECK(ci == (has_costs ? 3.0 : 1.0));
    const AccelInfo info = bvh.info();
    CHECK(info.sah_cost == Approx(ct + ci * 12.0 / 14.0));
    CHECK(info.nodes == 3);
    CHECK(info.leaves == 2);
    CHECK(info.max_depth == 1);
    CHECK(info.refs_per_prim == 1.0);
    CHECK(info.bytes_per_prim == Approx((3 * 32 + 2 * 4) / 2.0));
}

}  // namespace rtlab
