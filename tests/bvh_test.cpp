// BVH node layout, tree invariants and builder-specific edge cases.

#include "accel/any_accel.h"
#include "accel/bvh/build_common.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
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

/// The BVH of registry row `row` with max_leaf and any further settings (",key=value...").
Bvh build_with(const std::vector<Bounds3f>& boxes,
               const std::string& row,
               std::uint32_t max_leaf = 4,
               const std::string& more = "") {
    const std::string spec = row + ",max_leaf=" + std::to_string(max_leaf) + more;
    return std::get<Bvh>(build_accel(spec, BuildInput{boxes, {}}));
}

/// Checks what validate() cannot see without the input: every usable box is referenced, every
/// leaf box is the union of its primitives' boxes (with `spatial`, of their parts: inside that
/// union), inner node boxes are the tight unions of their children's, and inner nodes' children
/// are adjacent and stored after them.
void check_layout(const Bvh& bvh, const std::vector<Bounds3f>& boxes, bool spatial = false) {
    REQUIRE(bvh.validate().empty());
    std::vector<char> referenced(boxes.size(), 0);
    for (const std::uint32_t id : bvh.prim_ids) {
        referenced[id] = 1;
    }
    std::uint32_t unusable = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Bounds3f& b = boxes[i];
        const bool usable = is_finite(b.lo) && is_finite(b.hi) && b.lo.x <= b.hi.x &&
                            b.lo.y <= b.hi.y && b.lo.z <= b.hi.z;
        CHECK(static_cast<bool>(referenced[i]) == usable);
        unusable += usable ? 0 : 1;
    }
    CHECK(bvh.unreferenced_count == unusable);
    for (std::size_t n = 0; n < bvh.nodes.size(); ++n) {
        const BvhNode& node = bvh.nodes[n];
        Bounds3f tight;
        if (node.is_leaf()) {
            for (std::uint32_t s = node.first; s < node.first + node.prim_count(); ++s) {
                tight.extend(boxes[bvh.prim_ids[s]]);
            }
            if (spatial) {
                CHECK(tight.contains(node.bounds()));
                continue;
            }
        } else {
            CHECK(node.first > n);
            CHECK(node.first % 2 == 1);  // pairs start after the root: 1, 3, 5, ...
            tight = merge(bvh.nodes[node.first].bounds(), bvh.nodes[node.first + 1].bounds());
        }
        CHECK(tight == node.bounds());
    }
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
    const Bvh bvh = build_with(soup.boxes, builder, max_leaf);
    check_layout(bvh, soup.boxes, builder == "bvh:sbvh");
    CHECK(bvh == build_with(soup.boxes, builder, max_leaf));
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
    const double median = build_with(soup.boxes, "bvh:median").info().sah_cost;
    // All four measured with the same costs (Ct 1, Ci 1: the median and LBVH rows' Config).
    const double binned = build_with(soup.boxes, "bvh:binned", 4, ",ct=1").info().sah_cost;
    const double sweep = build_with(soup.boxes, "bvh:sweep", 4, ",ct=1").info().sah_cost;
    const double lbvh = build_with(soup.boxes, "bvh:lbvh").info().sah_cost;
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
    const Bvh bvh = build_with(soup.boxes, row, 8, costs);
    check_layout(bvh, soup.boxes);
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
    const Bvh bvh = build_with(soup.boxes, "bvh:binned", 4, ",bins=" + std::to_string(bins));
    check_layout(bvh, soup.boxes);
    CHECK(bvh.config.bin_count == bins);
    if (bins <= 1) {
        // One bin has no split candidate: the builder falls back to the object median.
        CHECK(bvh.nodes == build_with(soup.boxes, "bvh:median").nodes);
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
    const Bvh bvh = build_with(boxes, builder, 3);
    check_layout(bvh, boxes);
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
    const Bvh bvh = build_with(boxes, "bvh:lbvh", 2, ",morton_bits=2");
    check_layout(bvh, boxes);
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
        const Bvh bvh =
            build_with(boxes, "bvh:lbvh", 4, ",morton_bits=2,threads=" + std::to_string(threads));
        check_layout(bvh, boxes);
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
    const Bvh bvh = build_with(boxes, builder, 1);
    check_layout(bvh, boxes);
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
    const Bvh bvh = build_with(boxes, builder, 1);
    check_layout(bvh, boxes);
    CHECK(bvh.prim_ids.size() == 2);
    CHECK(bvh.unreferenced_count == 4);
    const Bvh none = build_with({Bounds3f{}, Bounds3f{}}, builder);
    CHECK(none.nodes.empty());
    CHECK(none.validate().empty());
    Rayf r{{-1, 0.5f, 0.5f}, {1, 0, 0}};
    CHECK_FALSE(none.intersect(r, [](std::uint32_t, Rayf&) { return true; }));
}

TEST_CASE("validate reports broken trees", "[accel][bvh]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 8, 50);
    const Bvh good = build_with(soup.boxes, "bvh:sweep");
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
    const Bvh source = build_with(soup.boxes, "bvh:binned");
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
    const Bvh bvh = build_with(boxes, "bvh:sweep", 1);
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
    const Bvh bvh = build_with(boxes, builder, 1, has_costs ? ",ct=2,ci=3" : "");
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

namespace rtlab {

TEST_CASE("parallel binned SAH builds the same tree for 1, 2 and 4 threads", "[accel][bvh]") {
    // 70000 primitives: above the builder's thresholds for parallel binning and partitioning
    // (65536) and for subtree tasks (4096), so every parallel path runs.
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    CAPTURE(static_cast<int>(kind));
    const test::Soup soup = test::random_soup(kind, 5, 70000);
    const Bvh one = build_with(soup.boxes, "bvh:pbinned", 4, ",threads=1");
    check_layout(one, soup.boxes);
    for (const int threads : {2, 4}) {
        CAPTURE(threads);
        CHECK(one ==
              build_with(soup.boxes, "bvh:pbinned", 4, ",threads=" + std::to_string(threads)));
    }
    CHECK(one == build_with(soup.boxes, "bvh:pbinned", 4, ",threads=0"));
    // The same SAH quality as the sequential binned builder, within a few percent.
    const double par = one.info().sah_cost;
    const double seq = build_with(soup.boxes, "bvh:binned").info().sah_cost;
    CAPTURE(par, seq);
    CHECK(par <= seq * 1.05);
}

TEST_CASE("top-down BVH builders build the same tree for 1, 2 and 4 threads", "[accel][bvh]") {
    // 70000 primitives: nodes above TopDown::parallel_min (4096) build their children as tasks
    // into one slot array (compacted after; one thread appends densely), and box unions over
    // 65536 or more primitives are reduced in parallel blocks.
    const std::string row =
        GENERATE(as<std::string>{}, "bvh:median", "bvh:binned", "bvh:sweep", "bvh:lbvh");
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    CAPTURE(row, static_cast<int>(kind));
    // Empty boxes spread over every block of the parallel collection of usable ids.
    std::vector<Bounds3f> boxes = test::random_soup(kind, 31, 70000).boxes;
    for (std::size_t i = 0; i < boxes.size(); i += 997) {
        boxes[i] = Bounds3f{};
    }
    const Bvh one = build_with(boxes, row, 4, ",threads=1");
    check_layout(one, boxes);
    CHECK(one.unreferenced_count == (boxes.size() + 996) / 997);
    for (const int threads : {2, 4, 0}) {
        CAPTURE(threads);
        const Bvh many = build_with(boxes, row, 4, ",threads=" + std::to_string(threads));
        check_layout(many, boxes);
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
    check_layout(before, boxes);
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
    // 200,000 keys (several 65536-key blocks), codes from few values so that ties are common,
    // ids in increasing order: the radix sort on the high 32 bits (3 passes of 11 bits) and on
    // 30 of them (3 of 10) equal std::stable_sort on those bits.
    const std::uint32_t bits = GENERATE(32u, 30u, 7u);
    CAPTURE(bits);
    test::Rng rng(bits);
    ScratchVector<std::uint64_t> keys(200000);
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
    const Bvh bvh = build_with(boxes, "bvh:sweep");
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

TEST_CASE("pair layout keeps the source tree: leaves, boxes and answers", "[accel][bvh]") {
    const std::string from = GENERATE("pbinned", "binned", "sweep", "lbvh", "median");
    const auto count = GENERATE(0u, 1u, 2u, 5u, 1000u);
    CAPTURE(from, count);
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 3, count);
    // The source's settings (max_leaf 4, Ct 1, 16 bins), not the pair row's defaults; leaves
    // packed as the source's (the default aligns them: align_leaf_slots, tested below).
    const std::string_view settings = "max_leaf=4,ct=1,bins=16,block=1";
    const Bvh source =
        std::get<Bvh>(build_accel(test::spec_with("bvh:" + from, settings), soup.input()));
    const AnyAccel any = build_accel(
        test::spec_with("bvh:pair", settings) + ",from=" + from + ",leaf_align=1", soup.input());
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
    const PairBvh pair = PairBvh::convert(build_with(boxes, "bvh:binned", 1));
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
    const Bvh source = build_with(boxes, "bvh:binned", 1);
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
