// Wide BVHs (BVH4, BVH8, BVH16, quantised BVH8): the SIMD node test of every level the CPU runs
// against the scalar slab test traversal uses, quantisation's enclosing boxes, collapse from every
// binary builder, and every level's traversal against brute force and against the other levels
// (same answers, same counts).

#include "accel/bvh/wide_bvh.h"

#include "accel/any_accel.h"
#include "base/simd.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"
#include "support/bvh_checks.h"
#include "support/registry_lists.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace rtlab {
namespace {

/// The levels this CPU runs, lowest first.
std::vector<SimdLevel> runnable_levels() {
    std::vector<SimdLevel> out;
    for (const SimdLevel l : simd_levels) {
        if (l <= simd_supported()) {
            out.push_back(l);
        }
    }
    return out;
}

/// wide_node_hits of level l (Node: WideNode<N> or QWideNode8).
template <bool IsRobust, class Node>
unsigned node_hits_at(
    SimdLevel l, const Node& n, const SlabRay<float>& r, float tmin, float tmax, float* tn) {
    switch (l) {
    case SimdLevel::avx512:
        return simd_avx512::wide_node_hits<IsRobust>(n, r, tmin, tmax, tn);
    case SimdLevel::avx2:
        return simd_avx2::wide_node_hits<IsRobust>(n, r, tmin, tmax, tn);
    case SimdLevel::sse2:
        break;
    }
    return simd_sse2::wide_node_hits<IsRobust>(n, r, tmin, tmax, tn);
}

/// Every level's node test of `node` against the scalar test traversal uses (clip_slabs<false>;
/// robust: clip_slabs_ahead from tmin >= 0, else clip_slabs<true>) on node.bounds(i) of the slots
/// in `slots`, per ray: the same hit slots and bit-identical entry distances.
template <bool IsRobust, class Node>
void check_node_hits(const Node& node, unsigned slots, const std::vector<Rayf>& rays) {
    constexpr unsigned N = Node::width;
    for (const Rayf& ray : rays) {
        if (!is_valid(ray)) {
            continue;
        }
        const SlabRay<float> sr(ray);
        const PaddedInv<float> padded(sr);
        const auto clip = [&](const Bounds3f& b, float& t0, float& t1) {
            return IsRobust && ray.tmin >= 0.0f ? clip_slabs_ahead(b.lo, b.hi, sr, padded, t0, t1)
                                                : clip_slabs<IsRobust>(b.lo, b.hi, sr, t0, t1);
        };
        unsigned want = 0;
        float want_t[N] = {};
        for (unsigned i = 0; i < N; ++i) {
            float t0 = ray.tmin, t1 = ray.tmax;
            const Bounds3f b = node.bounds(i);
            if (((slots >> i) & 1u) && clip(b, t0, t1)) {
                want |= 1u << i;
                want_t[i] = t0;
            }
        }
        for (const SimdLevel l : runnable_levels()) {
            CAPTURE(simd_name(l));
            alignas(64) float tn[N];
            const unsigned got = node_hits_at<IsRobust>(l, node, sr, ray.tmin, ray.tmax, tn);
            REQUIRE(got == want);
            for (unsigned i = 0; i < N; ++i) {
                if ((want >> i) & 1u) {
                    REQUIRE(std::bit_cast<std::uint32_t>(tn[i]) ==
                            std::bit_cast<std::uint32_t>(want_t[i]));
                }
            }
        }
    }
}

/// Each quantised slot encloses its box with the tightest codes: one code inward would not.
void check_quantised(const WideNode<8>& n, const QWideNode8& q) {
    for (unsigned i = 0; i < 8; ++i) {
        REQUIRE((((q.occupied >> i) & 1u) != 0) == n.occupied(i));
        if (!n.occupied(i) || n.bounds(i).empty()) {
            continue;
        }
        CAPTURE(i);
        REQUIRE(q.bounds(i).contains(n.bounds(i)));
        for (unsigned a = 0; a < 3; ++a) {
            const std::uint8_t lo = q.q[0][a][i], hi = q.q[1][a][i];
            if (q.scale[a] > 0.0f) {
                CHECK((lo == 255 || q.plane(a, static_cast<std::uint8_t>(lo + 1)) > n.lo[a][i]));
                CHECK((hi == 0 || q.plane(a, static_cast<std::uint8_t>(hi - 1)) < n.hi[a][i]));
            }
        }
    }
}

/// Nodes of N consecutive soup boxes: a WideNode (empty boxes included: they must miss), and
/// for N = 8 its quantised copy (non-empty boxes only) on its dequantised boxes, through
/// check_node_hits.
template <bool IsRobust, unsigned N>
void check_node_test(const test::Soup& soup, const std::vector<Rayf>& rays) {
    for (std::size_t first = 0; first + N <= soup.boxes.size(); first += N) {
        CAPTURE(first);
        WideNode<N> node = WideNode<N>::empty();
        WideNode<N> filled = WideNode<N>::empty();
        unsigned used = 0;
        for (unsigned i = 0; i < N; ++i) {
            const Bounds3f& b = soup.boxes[first + i];
            node.set(i, b, 0, 0);
            if (!b.empty()) {
                filled.set(used++, b, 0, 0);
            }
        }
        check_node_hits<IsRobust>(node, (1u << N) - 1u, rays);
        if constexpr (N == 8) {
            const QWideNode8 q = quantize_wide_node(filled);
            check_quantised(filled, q);
            check_node_hits<IsRobust>(q, q.occupied, rays);
        }
    }
}

TEST_CASE(
    "the SIMD node test of every level equals the scalar slab test bit for bit, quantised too",
    "[accel][wide]") {
    const auto seed = GENERATE(take(3, random(0u, 1u << 30)));
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, seed, 256);
    const std::vector<Rayf> rays = test::random_rays(soup, seed, 300);
    check_node_test<false, 4>(soup, rays);
    check_node_test<true, 4>(soup, rays);
    check_node_test<false, 8>(soup, rays);
    check_node_test<true, 8>(soup, rays);
    check_node_test<false, 16>(soup, rays);
    check_node_test<true, 16>(soup, rays);
    // Boxes on lattice planes, rays on their faces and along axes.
    const test::Soup lattice = test::lattice_soup({0, 0, 0.5f});
    const std::vector<Rayf> lrays = test::random_rays(lattice, seed, 300);
    check_node_test<false, 8>(lattice, lrays);
    check_node_test<true, 8>(lattice, lrays);
    check_node_test<false, 16>(lattice, lrays);
    check_node_test<true, 16>(lattice, lrays);
}

TEST_CASE("quantised nodes enclose extreme boxes tightly", "[accel][wide]") {
    const float big = std::numeric_limits<float>::max();
    const float tiny = std::numeric_limits<float>::denorm_min();
    const Bounds3f cases[][2] = {
        // Extents that overflow hi - lo, denormal and one-ulp boxes, flat axes.
        {{{-big, -big, -big}, {-1e38f, 0.0f, 1.0f}}, {{1e38f, 2.0f, 3.0f}, {big, big, big}}},
        {{{0.0f, 0.0f, 0.0f}, {tiny, tiny, 0.0f}},
         {{2 * tiny, 0.0f, 0.0f}, {5 * tiny, 0.0f, 0.0f}}},
        {{{1e6f, -1.0f, 7.0f}, {std::nextafter(1e6f, 2e6f), 1.0f, 7.0f}},
         {{std::nextafter(1e6f, 2e6f), -1.0f, 7.0f}, {std::nextafter(1e6f, 2e6f), 1.0f, 7.0f}}},
        {{{-3.0f, 1e-30f, -1e30f}, {-2.0f, 2e-30f, 1e30f}},
         {{5.0f, 1e-30f, 0.0f}, {6.0f, 1e-30f, 1e30f}}},
    };
    for (const auto& c : cases) {
        WideNode<8> n = WideNode<8>::empty();
        n.set(0, c[0], 7, 1);
        n.set(1, c[1], 9, 0);
        const QWideNode8 q = quantize_wide_node(n);
        check_quantised(n, q);
        CHECK(q.occupied == 3u);
        CHECK((q.child[0] == 7 && q.count[0] == 1 && q.child[1] == 9 && q.count[1] == 0));
    }
    WideNode<8> n = WideNode<8>::empty();
    n.set(0, {{0, 0, 0}, {1, 1, 1}}, 0, 70000);
    CHECK_THROWS_AS(quantize_wide_node(n), std::invalid_argument);
}

TEST_CASE("the 8-lane child order network sorts like lane_order_key", "[accel][wide][simd]") {
    test::Rng rng(11);
    const float pool[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -2.5f, 3.0f, 1e30f};
    for (int round = 0; round < 4000; ++round) {
        alignas(32) float t[8];
        for (float& x : t) {
            // Repeats from a small pool (ties, signed zeros) or values a few ulps apart.
            x = round % 2 == 0
                    ? pool[rng.below(8)]
                    : std::nextafter(1.0f, 2.0f) + static_cast<float>(rng.below(16)) * 1e-7f;
        }
        const unsigned mask = 1u + rng.below(255);
        std::vector<std::int32_t> want;
        for (unsigned i = 0; i < 8; ++i) {
            if ((mask >> i) & 1u) {
                want.push_back(lane_order_key(t[i], i));
            }
        }
        std::sort(want.begin(), want.end());
        alignas(32) std::int32_t got[8];
        const unsigned k = sort_lane_keys_scalar(t, mask, got);
        REQUIRE(std::vector<std::int32_t>(got, got + k) == want);
        for (const SimdLevel l : runnable_levels()) {
            CAPTURE(simd_name(l), mask);
            const unsigned n = l == SimdLevel::avx512 ? simd_avx512::sort_lane_keys8(t, mask, got)
                               : l == SimdLevel::avx2 ? simd_avx2::sort_lane_keys8(t, mask, got)
                                                      : simd_sse2::sort_lane_keys8(t, mask, got);
            REQUIRE(std::vector<std::int32_t>(got, got + n) == want);
        }
    }
    // Keys order by t (signed zeros aside), then by lane.
    CHECK(lane_order_key(-1.0f, 7) < lane_order_key(-0.5f, 0));
    CHECK(lane_order_key(-0.5f, 7) < lane_order_key(0.0f, 0));
    CHECK(lane_order_key(1.0f, 0) < lane_order_key(1.0f, 1));
    CHECK(lane_order_key(1.0f, 7) < lane_order_key(2.0f, 0));
}

TEST_CASE("16-lane child order keys sort by distance, then lane", "[accel][wide][simd]") {
    test::Rng rng(12);
    for (int round = 0; round < 2000; ++round) {
        alignas(64) float t[16];
        for (float& x : t) {
            // Ties and values a few ulps apart (within 16 ulps the lane decides).
            x = round % 2 == 0
                    ? static_cast<float>(rng.below(4))
                    : std::nextafter(1.0f, 2.0f) + static_cast<float>(rng.below(64)) * 1e-7f;
        }
        const unsigned mask = 1u + rng.below(65535);
        std::int32_t got[16];
        const unsigned k = sort_lane_keys_scalar<16>(t, mask, got);
        REQUIRE(k == static_cast<unsigned>(std::popcount(mask)));
        unsigned seen = 0;
        for (unsigned i = 0; i < k; ++i) {
            const auto lane = static_cast<unsigned>(got[i]) & 15u;
            REQUIRE(((mask >> lane) & 1u) != 0);
            seen |= 1u << lane;
            REQUIRE(got[i] == lane_order_key<16>(t[lane], lane));
            if (i > 0) {
                const auto prev = static_cast<unsigned>(got[i - 1]) & 15u;
                REQUIRE(got[i - 1] < got[i]);
                // Nearer first, but for distances within 16 ulps (these are >= 0), which go in
                // lane order.
                if (t[prev] >= t[lane]) {
                    REQUIRE(std::bit_cast<std::int32_t>(t[prev]) -
                                std::bit_cast<std::int32_t>(t[lane]) <
                            16);
                    REQUIRE(prev < lane);
                }
            }
        }
        REQUIRE(seen == mask);
    }
    CHECK(lane_order_key<16>(1.0f, 15) < lane_order_key<16>(2.0f, 0));
    CHECK(lane_order_key<16>(-1.0f, 15) < lane_order_key<16>(-0.5f, 0));
}

TEST_CASE("wide BVHs collapse every binary builder into valid, shallower trees", "[accel][wide]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 7, 2000);
    // The binary tree's settings (the wide rows default to larger leaves, Ct and blocks; the
    // median and LBVH rows have no SAH settings).
    const std::string_view source = "max_leaf=4,ct=1,block=1";
    for (const std::string& from : test::from_choices()) {
        const AnyAccel binary = build_accel(test::spec_with("bvh:" + from, source), soup.input());
        const AccelInfo bi = accel_info(binary);
        for (const char* wide : {"bvh4", "bvh8", "bvh16", "bvh8q"}) {
            CAPTURE(from, wide);
            const AnyAccel w = build_accel(
                test::spec_with(wide, "from=" + from + "," + std::string(source)), soup.input());
            REQUIRE(accel_validate(w).empty());
            const AccelInfo wi = accel_info(w);
            CHECK(wi.leaves == bi.leaves);  // leaves are kept as the binary build made them
            CHECK(wi.nodes < bi.nodes / 2);
            CHECK(wi.max_depth < bi.max_depth);
            CHECK(wi.sah_cost > 0);
            CHECK(accel_bounds(w) == accel_bounds(binary));
        }
    }
}

/// Pairs of neighbouring occupied slots in w whose first box has the smaller surface area.
template <unsigned N>
std::size_t slots_out_of_area_order(const WideBvh<N>& w) {
    std::size_t out = 0;
    for (const WideNode<N>& n : w.nodes) {
        for (unsigned i = 1; i < N && n.occupied(i); ++i) {
            out += n.bounds(i - 1).surface_area() < n.bounds(i).surface_area() ? 1 : 0;
        }
    }
    return out;
}

template <unsigned N>
void check_area_order(const test::Soup& soup, const std::string& wide) {
    CAPTURE(wide);
    const AnyAccel area = build_accel(wide, soup.input());
    const AnyAccel build = build_accel(wide + ",order=build", soup.input());
    REQUIRE(accel_validate(area).empty());
    REQUIRE(accel_validate(build).empty());
    // The order moves slots only: the same nodes, leaves and cost.
    const AccelInfo ai = accel_info(area), bi = accel_info(build);
    CHECK(ai.nodes == bi.nodes);
    CHECK(ai.leaves == bi.leaves);
    CHECK(ai.sah_cost == bi.sah_cost);
    CHECK(slots_out_of_area_order(std::get<WideBvh<N>>(area)) == 0);
    // The source order is not sorted already, so the check above can fail.
    CHECK(slots_out_of_area_order(std::get<WideBvh<N>>(build)) > 0);
}

TEST_CASE("wide BVH children are ordered by surface area, largest first", "[accel][wide]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 9, 3000);
    check_area_order<4>(soup, "bvh4");
    check_area_order<8>(soup, "bvh8");
    check_area_order<16>(soup, "bvh16");
}

TEST_CASE("wide BVHs are the same nodes for any thread count", "[accel][wide]") {
    // Deep enough that the subtrees below the serial top levels are collapsed by parallel tasks.
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 5, 20000);
    for (const std::string wide :
         {"bvh4", "bvh8", "bvh16", "bvh8q", "bvh8,collapse=greedy", "bvh16,bounds=dop14"}) {
        CAPTURE(wide);
        const std::string spec = wide + ",max_leaf=4,ct=1,threads=";
        const AnyAccel one = build_accel(spec + "1", soup.input());
        REQUIRE(accel_validate(one).empty());
        // Below the collapse's serial top levels (3 for BVH4, 2 for BVH8, 1 for BVH16).
        REQUIRE(accel_info(one).max_depth > (wide.starts_with("bvh16") ? 2 : 4));
        for (const char* threads : {"2", "4", "0"}) {
            CAPTURE(threads);
            CHECK(build_accel(spec + threads, soup.input()) == one);
        }
    }
}

/// The summed surface area of w's nodes: the root's (its children's union) and every inner slot's.
template <unsigned N>
double wide_node_area(const WideBvh<N>& w) {
    Bounds3f root;
    for (unsigned i = 0; i < N && w.nodes[0].occupied(i); ++i) {
        root = merge(root, w.nodes[0].bounds(i));
    }
    double sum = static_cast<double>(root.surface_area());
    for (const WideNode<N>& n : w.nodes) {
        for (unsigned i = 0; i < N && n.occupied(i); ++i) {
            sum += n.is_leaf(i) ? 0.0 : static_cast<double>(n.bounds(i).surface_area());
        }
    }
    return sum;
}

/// The least summed surface area of the wide nodes of any collapse of `bvh` into nodes of at most
/// N children, by trying every set of the inner nodes below the root as the other wide nodes: a
/// wide node's children are the leaves and wide nodes reached through the other inner nodes.
template <unsigned N>
double least_collapse_area(const Bvh& bvh) {
    std::vector<std::uint32_t> inner;
    for (std::uint32_t i = 1; i < bvh.nodes.size(); ++i) {
        if (!bvh.nodes[i].is_leaf()) {
            inner.push_back(i);
        }
    }
    REQUIRE(inner.size() <= 16);
    double best = std::numeric_limits<double>::infinity();
    std::vector<char> wide(bvh.nodes.size());
    for (std::uint32_t set = 0; set < (1u << inner.size()); ++set) {
        std::fill(wide.begin(), wide.end(), 0);
        wide[0] = 1;
        for (std::size_t k = 0; k < inner.size(); ++k) {
            wide[inner[k]] = static_cast<char>((set >> k) & 1u);
        }
        const auto kids = [&](auto&& self, std::uint32_t b) -> unsigned {
            unsigned n = 0;
            for (const std::uint32_t c : {bvh.nodes[b].first, bvh.nodes[b].first + 1}) {
                n += bvh.nodes[c].is_leaf() || wide[c] ? 1 : self(self, c);
            }
            return n;
        };
        double sum = 0;
        bool fits = true;
        for (std::uint32_t b = 0; b < bvh.nodes.size(); ++b) {
            if (wide[b] != 0) {
                fits = fits && kids(kids, b) <= N;
                sum += static_cast<double>(bvh.nodes[b].bounds().surface_area());
            }
        }
        if (fits) {
            best = std::min(best, sum);
        }
    }
    return best;
}

TEST_CASE("the sah collapse has the least node area of any collapse", "[accel][wide]") {
    const auto seed = GENERATE(take(6, random(0u, 1u << 30)));
    CAPTURE(seed);
    // Small trees (leaves of one box: up to 16 inner nodes below the root) against every collapse.
    const test::Soup small = test::random_soup(test::SoupKind::boxes, seed, 15);
    const Bvh binary = test::build_with(small.boxes, "bvh:binned", 1);
    REQUIRE(binary.nodes.size() > 20);
    const auto check_least = [&]<unsigned N>(std::integral_constant<unsigned, N>) {
        CAPTURE(N);
        const WideBvh<N> sah = collapse_bvh<N>(binary, ChildOrder::area, WideCollapse::sah);
        REQUIRE(sah.validate().empty());
        CHECK(wide_node_area(sah) == Approx(least_collapse_area<N>(binary)).epsilon(1e-6));
    };
    check_least(std::integral_constant<unsigned, 4>{});
    check_least(std::integral_constant<unsigned, 8>{});
    // Larger trees: never more than the greedy collapse's, and less in some.
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, seed, 3000);
    const Bvh source = test::build_with(soup.boxes, "bvh:binned", 4);
    const auto check_greedy = [&]<unsigned N>(std::integral_constant<unsigned, N>) {
        CAPTURE(N);
        const WideBvh<N> sah = collapse_bvh<N>(source, ChildOrder::area, WideCollapse::sah);
        const WideBvh<N> greedy = collapse_bvh<N>(source, ChildOrder::area, WideCollapse::greedy);
        REQUIRE(sah.validate().empty());
        CHECK(wide_node_area(sah) < wide_node_area(greedy));
        CHECK(sah.prim_ids == greedy.prim_ids);  // the same leaves
    };
    check_greedy(std::integral_constant<unsigned, 4>{});
    check_greedy(std::integral_constant<unsigned, 8>{});
    check_greedy(std::integral_constant<unsigned, 16>{});
}

TEST_CASE("wide BVH validate() finds broken invariants", "[accel][wide]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 3, 300);
    const WideBvh<8> good = std::get<WideBvh<8>>(build_accel("bvh8", soup.input()));
    REQUIRE(good.validate().empty());
    WideBvh<8> b = good;
    b.nodes[0].lo[0][0] -= 1.0f;  // still fine: the root has no parent box
    CHECK(b.validate().empty());
    b = good;
    b.prim_ids[0] = b.prim_ids[1];
    CHECK(!b.validate().empty());
    b = good;
    std::uint32_t inner = 0;
    while (b.nodes[0].is_leaf(inner)) {
        ++inner;
    }
    const std::uint32_t child = b.nodes[0].child[inner];
    b.nodes[child].hi[1][0] = b.nodes[0].hi[1][inner] + 1.0f;
    CHECK(b.validate().find("outside") != std::string::npos);
    b = good;
    b.nodes[child].child[1] = WideNode<8>::empty_slot;
    CHECK(!b.validate().empty());
    // Quantised copies: one per node, the same children, boxes enclosing the nodes'.
    WideBvh<8> q = std::get<WideBvh<8>>(build_accel("bvh8q", soup.input()));
    REQUIRE(q.nodes == good.nodes);
    REQUIRE(q.qnodes.size() == good.nodes.size());
    REQUIRE(q.validate().empty());
    b = q;
    b.qnodes.pop_back();
    CHECK(b.validate().find("quantised nodes") != std::string::npos);
    b = q;
    b.qnodes[0].count[0] = static_cast<std::uint16_t>(b.qnodes[0].count[0] + 1);
    CHECK(b.validate().find("differs") != std::string::npos);
    b = q;
    b.qnodes[0].scale[0] *= 0.5f;  // planes pulled inward
    CHECK(b.validate().find("enclose") != std::string::npos);
}

TEST_CASE("diagonal slabs hold every primitive of their slot and break validate() when cut",
          "[accel][wide]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 11, 3000);
    const AnyAccel a = build_accel("bvh16,bounds=dop14,max_leaf=4", soup.input());
    REQUIRE(accel_validate(a).empty());
    const auto& w = std::get<WideBvh<16>>(a);
    REQUIRE(w.diags.size() == w.nodes.size());
    REQUIRE(build_accel("bvh16", soup.input()) != a);  // the same nodes, plus the slabs
    // Every vertex of every triangle in a leaf slot lies inside the slot's slabs (in double).
    std::size_t checked = 0, tighter = 0;
    for (std::size_t node = 0; node < w.nodes.size(); ++node) {
        const WideNode<16>& n = w.nodes[node];
        for (unsigned i = 0; i < 16 && n.occupied(i); ++i) {
            const Bounds3f box = n.bounds(i);
            for (unsigned k = 0; k < 4; ++k) {
                // The box's own extent in this direction: the slabs cut it where they are below.
                const double box_lo = diag_dot(k, diag_corner(box, k, true));
                tighter += static_cast<double>(w.diags[node].lo[k][i]) > box_lo ? 1 : 0;
                if (!n.is_leaf(i)) {
                    continue;
                }
                for (std::uint32_t s = n.child[i]; s < n.child[i] + n.count[i]; ++s) {
                    if (w.prim_ids[s] == padding_slot) {
                        continue;
                    }
                    const auto& t = soup.triangles[w.prim_ids[s]];
                    for (const Vec3f& p : {t.p0, t.p1, t.p2}) {
                        CHECK(diag_dot(k, p) >= static_cast<double>(w.diags[node].lo[k][i]));
                        CHECK(diag_dot(k, p) <= static_cast<double>(w.diags[node].hi[k][i]));
                        ++checked;
                    }
                }
            }
        }
    }
    CHECK(checked >= 3 * 4 * 3000);
    CHECK(tighter > 0);  // the slabs cut some boxes' corners
    // Slabs cut inward, or left on an empty slot, are found.
    WideBvh<16> b = w;
    b.diags[0].hi[2][0] = b.diags[0].lo[2][0] - 1.0f;
    CHECK(b.validate().find("diagonal") != std::string::npos);
    b = w;
    const std::uint32_t inner = [&] {
        for (unsigned i = 0; i < 16; ++i) {
            if (w.nodes[0].occupied(i) && !w.nodes[0].is_leaf(i)) {
                return i;
            }
        }
        return 0u;
    }();
    b.diags[0].lo[1][inner] = b.diags[0].hi[1][inner];
    CHECK(b.validate().find("outside its parent") != std::string::npos);
    b = w;
    b.diags.pop_back();
    CHECK(b.validate().find("diagonal slab sets") != std::string::npos);
}

TEST_CASE("every SIMD level of the wide BVHs agrees with brute force and with the others",
          "[accel][wide]") {
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const auto count = GENERATE(1u, 9u, 700u);
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(static_cast<int>(kind), count, seed);
    const test::Soup soup = test::random_soup(kind, seed, count);
    const std::vector<Rayf> rays = test::random_rays(soup, seed, 300);
    for (const char* spec :
         {"bvh4", "bvh8", "bvh16", "bvh8q", "bvh8,from=lbvh,max_leaf=1",
          "bvh16,from=lbvh,max_leaf=1", "bvh4,from=sweep", "bvh8,collapse=greedy",
          "bvh16,collapse=greedy", "bvh4,collapse=greedy,from=lbvh,max_leaf=1",
          "bvh16,bounds=dop14", "bvh8,bounds=dop14", "bvh4,bounds=dop14,from=lbvh,max_leaf=1"}) {
        CAPTURE(spec);
        const AnyAccel accel = build_accel(spec, soup.input());
        REQUIRE(accel_validate(accel).empty());
        std::vector<Hit> first_hits;
        std::vector<TraversalStats> first_stats;
        for (const SimdLevel l : runnable_levels()) {
            CAPTURE(simd_name(l));
            const ScopedSimdCap cap(l);
            REQUIRE(simd_level() == l);
            visit_accel(accel, [&](const auto& s) {
                test::check_agrees_with_brute_force(s, soup, rays);
                for (std::size_t i = 0; i < rays.size(); ++i) {
                    Hit h;
                    Rayf r = rays[i];
                    TraversalStats st;
                    s.template intersect<true>(r, soup.closest_hit(h), st);
                    if (l == SimdLevel::sse2) {
                        first_hits.push_back(h);
                        first_stats.push_back(st);
                    } else {
                        REQUIRE(h.prim == first_hits[i].prim);
                        REQUIRE(h.t == first_hits[i].t);
                        REQUIRE(st.nodes == first_stats[i].nodes);
                        REQUIRE(st.prims == first_stats[i].prims);
                    }
                }
            });
        }
    }
}

}  // namespace
}  // namespace rtlab
