// kd-tree (SAH and spatial-median builders): agreement with brute force on seeded soups, with and
// without exact triangle clipping (perfect splits); rays on split planes; the hit beyond the
// first leaf a primitive overlaps; invariants, determinism and traversal counts.

#include "accel/any_accel.h"
#include "accel/brute_force.h"
#include "accel/kdtree/events.h"
#include "support/accel_checks.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {
namespace {

/// The kd-tree registry rows.
const std::vector<std::string> kd_rows{"kdtree:sah", "kdtree:median"};

/// The traversal settings, each appended to a row.
const std::vector<std::string> kd_walks{",traversal=havran", ",traversal=tvalue"};

/// The kd-tree built by spec (a registry row name, optionally with ",key=value" settings).
KdTree build_kd(const std::string& spec, const BuildInput& in) {
    return std::get<KdTree>(build_accel(spec, in));
}

/// Bounds of the part of triangle t inside box (Sutherland–Hodgman against the six planes, in
/// double, rounded outwards to float), intersected with box; empty when the parts are disjoint.
Bounds3f clip_triangle(const MollerTrumbore<float>::Prepared& t, const Bounds3f& box) {
    std::vector<Vec3d> poly{Vec3d(t.p0), Vec3d(t.p1), Vec3d(t.p2)}, next;
    for (std::size_t a = 0; a < 3; ++a) {
        for (const bool upper : {false, true}) {
            const double plane = static_cast<double>(upper ? box.hi[a] : box.lo[a]);
            const auto inside = [&](const Vec3d& p) {
                return upper ? p[a] <= plane : p[a] >= plane;
            };
            next.clear();
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const Vec3d& p = poly[i];
                const Vec3d& q = poly[(i + 1) % poly.size()];
                if (inside(p)) {
                    next.push_back(p);
                }
                if (inside(p) != inside(q)) {
                    Vec3d x = p + (q - p) * ((plane - p[a]) / (q[a] - p[a]));
                    x[a] = plane;
                    next.push_back(x);
                }
            }
            poly.swap(next);
            if (poly.empty()) {
                return {};
            }
        }
    }
    Bounds3f b;
    for (const Vec3d& p : poly) {
        for (std::size_t a = 0; a < 3; ++a) {
            const auto f = static_cast<float>(p[a]);
            const float lo = static_cast<double>(f) > p[a] ? std::nextafter(f, -HUGE_VALF) : f;
            const float hi = static_cast<double>(f) < p[a] ? std::nextafter(f, HUGE_VALF) : f;
            b.lo[a] = std::min(b.lo[a], lo);
            b.hi[a] = std::max(b.hi[a], hi);
        }
    }
    return intersection(b, box);
}

/// The soup's BuildInput, with the exact triangle clip when asked (boxes: box ∩ cell).
BuildInput make_input(const test::Soup& soup, bool exact_clip) {
    BuildInput in = soup.input();
    if (exact_clip) {
        in.clip = [&soup](std::uint32_t id, const Bounds3f& box) {
            if (soup.kind == test::SoupKind::triangles) {
                return clip_triangle(soup.triangles[id], box);
            }
            return intersection(soup.boxes[id], box);
        };
    }
    return in;
}

/// Rays starting on split planes of `tree`: lying in the plane, crossing it, and axis-aligned.
std::vector<Rayf> split_plane_rays(const KdTree& tree, std::uint64_t seed, std::size_t count) {
    test::Rng rng(seed);
    std::vector<Rayf> rays;
    const Bounds3f& box = tree.scene_bounds;
    for (std::size_t i = 0; i < tree.nodes.size() && rays.size() < count; ++i) {
        const KdNode& n = tree.nodes[i];
        if (n.is_leaf()) {
            continue;
        }
        Rayf r;
        r.org = rng.point_in(box);
        r.org[n.axis()] = n.split();
        r.dir = rng.direction();
        switch (rays.size() % 3) {
        case 0:  // in the plane
            r.dir[n.axis()] = 0;
            break;
        case 1:  // axis-aligned, in the plane
            r.dir = {0, 0, 0};
            r.dir[(n.axis() + 1 + rng.below(2)) % 3] = rng.below(2) ? 1.0f : -1.0f;
            break;
        default:  // crossing it from the plane
            break;
        }
        if (length_squared(r.dir) == 0.0f) {
            r.dir[(n.axis() + 1) % 3] = 1;
        }
        rays.push_back(r);
    }
    return rays;
}

}  // namespace

TEST_CASE("kd-tree nodes are 8 bytes and round-trip their fields", "[accel][kdtree]") {
    STATIC_REQUIRE(sizeof(KdNode) == 8);
    const KdNode inner = KdNode::inner(2, -0.375f, KdNode::max_index);
    CHECK_FALSE(inner.is_leaf());
    CHECK(inner.axis() == 2);
    CHECK(inner.split() == -0.375f);
    CHECK(inner.above_child() == KdNode::max_index);
    const KdNode leaf = KdNode::leaf(123456789u, 77);
    CHECK(leaf.is_leaf());
    CHECK(leaf.prim_offset() == 123456789u);
    CHECK(leaf.prim_count() == 77);
}

TEST_CASE("kd-tree agrees with brute force", "[accel][kdtree]") {
    const std::string row = GENERATE(from_range(kd_rows));
    const std::string builder = row + GENERATE(as<std::string>{}, ",perfect=1", ",perfect=0") +
                                GENERATE(from_range(kd_walks));
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const bool exact_clip = GENERATE(false, true);
    const auto count = GENERATE(1u, 2u, 17u, 500u);
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(builder, static_cast<int>(kind), exact_clip, count, seed);
    const test::Soup soup = test::random_soup(kind, seed, count);
    const BuildInput in = make_input(soup, exact_clip);
    const KdTree tree = build_kd(builder, in);
    REQUIRE(tree.validate().empty());
    REQUIRE(tree == build_kd(builder, in));
    const AccelInfo info = tree.info();
    CHECK(info.nodes == tree.nodes.size());
    CHECK(info.max_depth <= tree.max_depth);
    CHECK(info.refs_per_prim >= 1.0);

    std::vector<Rayf> rays = test::random_rays(soup, seed, 200);
    const std::vector<Rayf> on_planes = split_plane_rays(tree, seed, 60);
    rays.insert(rays.end(), on_planes.begin(), on_planes.end());
    test::check_agrees_with_brute_force(tree, soup, rays);
}

TEST_CASE("kd-tree leaf ranges offer the slots of the per-id walk, in order", "[accel][kdtree]") {
    // intersect_leaves / occluded_leaves (what tracers with slot-ordered triangles call) against
    // intersect / occluded on the same tree: the same primitives offered in the same order, the
    // same answers and counts, for both walks, plain and robust.
    const std::string walk = GENERATE(from_range(kd_walks));
    const auto seed = GENERATE(take(2, random(0u, 1u << 30)));
    CAPTURE(walk, seed);
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, seed, 400);
    const KdTree tree = build_kd("kdtree:sah" + walk, make_input(soup, true));
    std::vector<Rayf> rays = test::random_rays(soup, seed, 200);
    const std::vector<Rayf> on_planes = split_plane_rays(tree, seed, 60);
    rays.insert(rays.end(), on_planes.begin(), on_planes.end());
    std::size_t offered_total = 0;
    for (const bool robust : {false, true}) {
        for (const Rayf& ray : rays) {
            CAPTURE(robust, ray.org.x, ray.org.y, ray.org.z, ray.dir.x, ray.dir.y, ray.dir.z);
            std::vector<std::uint32_t> by_id, by_range;
            Hit want, got;
            const auto record = soup.closest_hit(want);
            const auto id_fn = [&](std::uint32_t id, Rayf& r) {
                by_id.push_back(id);
                return record(id, r);
            };
            const auto range_fn = [&](std::uint32_t first, std::uint32_t count, Rayf& r) {
                bool hit = false;
                for (std::uint32_t s = first; s < first + count; ++s) {
                    by_range.push_back(tree.prim_ids[s]);
                    if (const auto h = soup.hit(tree.prim_ids[s], r)) {
                        r.tmax = h->t;
                        got = {h->t, h->u, h->v, tree.prim_ids[s]};
                        hit = true;
                    }
                }
                return hit;
            };
            TraversalStats st_id, st_range;
            Rayf r1 = ray, r2 = ray;
            const bool h1 = robust ? tree.intersect<true>(r1, id_fn, st_id)
                                   : tree.intersect<false>(r1, id_fn, st_id);
            const bool h2 = robust ? tree.intersect_leaves<true>(r2, range_fn, st_range)
                                   : tree.intersect_leaves<false>(r2, range_fn, st_range);
            REQUIRE(h1 == h2);
            REQUIRE(by_id == by_range);
            CHECK(st_id.nodes == st_range.nodes);
            CHECK(st_id.prims == st_range.prims);
            if (h1) {
                CHECK(got.prim == want.prim);
                CHECK(got.t == want.t);
            }
            offered_total += by_id.size();
            const auto any_range = [&](std::uint32_t first, std::uint32_t count, const Rayf& r) {
                for (std::uint32_t s = first; s < first + count; ++s) {
                    if (soup.hit(tree.prim_ids[s], r)) {
                        return true;
                    }
                }
                return false;
            };
            const bool o1 = robust ? tree.occluded<true>(ray, soup.any_hit())
                                   : tree.occluded<false>(ray, soup.any_hit());
            const bool o2 = robust ? tree.occluded_leaves<true>(ray, any_range)
                                   : tree.occluded_leaves<false>(ray, any_range);
            CHECK(o1 == o2);
        }
    }
    CHECK(offered_total > rays.size());  // the rays really reach leaves
}

TEST_CASE("kd-tree events sort as their integers, ties in primitive order", "[accel][kdtree]") {
    using namespace kd_detail;
    test::Rng rng(17);
    const float positions[] = {-1.5f, -0.0f, 0.0f, 0.25f, 3.0f, -HUGE_VALF, HUGE_VALF};
    for (const std::size_t n : {std::size_t{10}, std::size_t{5000}}) {
        std::vector<Event> v;
        for (std::uint32_t id = 0; id < n; ++id) {  // generated in id order, as the builder does
            const float p = rng.below(4) == 0 ? positions[rng.below(7)] : rng.uniform(-4, 4);
            v.push_back(make_event(p, static_cast<EventType>(rng.below(3)), id));
        }
        std::vector<Event> want = v;
        std::sort(want.begin(), want.end());
        sort_events(v);
        REQUIRE(v == want);
        for (std::size_t i = 1; i < v.size(); ++i) {
            const float a = event_pos(v[i - 1]), b = event_pos(v[i]);
            REQUIRE(a <= b);
            if (a == b && event_type(v[i - 1]) == event_type(v[i])) {
                REQUIRE(event_prim(v[i - 1]) < event_prim(v[i]));
            }
        }
    }
    CHECK(event_pos(make_event(-0.0f, event_start, 5)) == 0.0f);
    CHECK(event_pos_bits(make_event(-0.0f, event_end, 1)) ==
          event_pos_bits(make_event(0.0f, event_end, 1)));
    CHECK(event_prim(make_event(1.0f, event_planar, KdNode::max_index)) == KdNode::max_index);
}

TEST_CASE("kd-tree SAH and median builds are the same tree for any thread count",
          "[accel][kdtree]") {
    // Large enough for parallel subtree tasks (nodes of 4096 primitives and more).
    const auto kind = GENERATE(test::SoupKind::boxes, test::SoupKind::triangles);
    const std::string perfect = GENERATE(as<std::string>{}, ",perfect=1", ",perfect=0");
    CAPTURE(static_cast<int>(kind), perfect);
    const test::Soup soup = test::random_soup(kind, 23, 20000);
    const BuildInput in = make_input(soup, true);
    const KdTree one = build_kd("kdtree:sah,threads=1" + perfect, in);
    REQUIRE(one.validate().empty());
    REQUIRE(one.nodes.size() > 1000);
    CHECK(one == build_kd("kdtree:sah,threads=2" + perfect, in));
    CHECK(one == build_kd("kdtree:sah,threads=4" + perfect, in));
    CHECK(one == build_kd("kdtree:sah" + perfect, in));
    const KdTree median = build_kd("kdtree:median,threads=1" + perfect, in);
    REQUIRE(median.validate().empty());
    CHECK(median == build_kd("kdtree:median,threads=2" + perfect, in));
    CHECK(median == build_kd("kdtree:median,threads=4" + perfect, in));
    test::check_agrees_with_brute_force(one, soup, test::random_rays(soup, 23, 300));
}

TEST_CASE("kd-tree perfect splits reference fewer leaves for triangles", "[accel][kdtree]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 31, 3000);
    const BuildInput in = make_input(soup, true);
    const KdTree on = build_kd("kdtree:sah,perfect=1", in);
    const KdTree off = build_kd("kdtree:sah,perfect=0", in);
    REQUIRE(on.validate().empty());
    REQUIRE(off.validate().empty());
    // Clipping can only shrink a straddler's part, so the same plane never adds references;
    // the trees differ, but the SAH cost of the clipped one is lower on triangles.
    CHECK(on.info().sah_cost < off.info().sah_cost);
    // Without a clip function the option has nothing to clip: both build the box-cut tree.
    CHECK(build_kd("kdtree:sah,perfect=1", soup.input()) ==
          build_kd("kdtree:sah,perfect=0", soup.input()));
}

TEST_CASE("kd-tree handles primitives and rays on shared planes", "[accel][kdtree]") {
    // Unit boxes of a 4x4x4 lattice (every other cell), flat boxes in lattice planes, duplicates
    // and point boxes on lattice corners: every split candidate is a shared face.
    const test::Soup soup = test::lattice_soup({1, 1, 0});  // flat boxes in the plane z = 1
    test::Rng rng(5);
    std::vector<Rayf> rays;
    for (int i = 0; i < 300; ++i) {
        Rayf r;
        r.org = {static_cast<float>(rng.below(5)), static_cast<float>(rng.below(5)),
                 static_cast<float>(rng.below(5))};
        const std::size_t a = rng.below(3);
        if (i % 3 == 0) {
            r.dir[a] = rng.below(2) ? 1.0f : -1.0f;  // along lattice lines
        } else {
            r.dir = rng.direction();
            if (i % 3 == 1) {
                r.dir[a] = 0;  // in a lattice plane
            }
            r.org[(a + 1) % 3] += rng.uniform(0, 1);
        }
        if (i % 5 == 0) {
            r.tmin = rng.uniform(0, 2);
            r.tmax = r.tmin + rng.uniform(0, 0.5f);
        }
        rays.push_back(r);
    }
    for (const std::string& row : kd_rows) {
        for (const std::string& walk : kd_walks) {
            CAPTURE(row, walk);
            const KdTree tree = build_kd(row + walk, soup.input());
            REQUIRE(tree.validate().empty());
            test::check_agrees_with_brute_force(tree, soup, rays);
            test::check_agrees_with_brute_force(tree, soup, split_plane_rays(tree, 9, 200));
        }
    }
}

TEST_CASE("kd-tree finds a near hit beyond the first leaf of a long primitive", "[accel][kdtree]") {
    // A long slanted triangle L whose box covers the scene is hit by the ray at x = 9; a small
    // triangle S at x = 5 (or 9.5) lies on the same ray. Filler triangles along x force splits,
    // so L is offered in the first leaf, with its hit several leaves further on.
    const float s_x = GENERATE(5.0f, 9.5f);
    const bool exact_clip = GENERATE(false, true);
    CAPTURE(s_x, exact_clip);
    const test::Soup soup = test::long_primitive_soup(s_x);
    // Slightly slanted too, so the TA^B_rec walk runs (a zero direction component takes the
    // t-value walk).
    const Rayf ray =
        GENERATE(Rayf{{-1, 0.5f, 0.5f}, {1, 0, 0}}, Rayf{{-1, 0.5f, 0.5f}, {1, 1e-4f, 1e-4f}});
    for (const std::string& builder : {kd_rows[0] + kd_walks[0], kd_rows[0] + kd_walks[1],
                                       kd_rows[1] + kd_walks[0], kd_rows[1] + kd_walks[1]}) {
        CAPTURE(builder);
        const KdTree tree = build_kd(builder, make_input(soup, exact_clip));
        REQUIRE(tree.validate().empty());
        REQUIRE(tree.nodes.size() > 8);
        std::vector<std::uint32_t> order;
        Hit h;
        Rayf r = ray;
        const auto record = soup.closest_hit(h);
        const bool hit = tree.intersect(r, [&](std::uint32_t id, Rayf& rr) {
            order.push_back(id);
            return record(id, rr);
        });
        REQUIRE(hit);
        if (s_x < 9.0f) {
            CHECK(h.prim == 1u);
            CHECK(h.t == Approx(s_x + 1.0f).epsilon(1e-3));
            // The case really happened: L was offered (and hit far away) before S was. (With
            // exact clipping the leaves before S's need not hold L.)
            if (!exact_clip) {
                REQUIRE(order.size() >= 2);
                CHECK(order.front() == 0u);
            }
        } else {
            CHECK(h.prim == 0u);
            CHECK(h.t == Approx(10.0f).epsilon(1e-3));
        }
        CHECK(tree.occluded(ray, soup.any_hit()));
    }
}

TEST_CASE("kd-tree of no usable primitive is empty and never hit", "[accel][kdtree]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<Bounds3f> boxes{Bounds3f{}, {{nan, 0, 0}, {1, 1, 1}}};
    for (const std::string& builder : kd_rows) {
        for (const std::size_t n : {std::size_t{0}, std::size_t{2}}) {
            const KdTree tree = build_kd(builder, {std::span(boxes).first(n), {}});
            CHECK(tree.validate().empty());
            Rayf r{{-1, 0.5f, 0.5f}, {1, 0, 0}};
            TraversalStats st;
            CHECK_FALSE(tree.intersect(
                r, [](std::uint32_t, Rayf&) { return true; }, st));
            CHECK_FALSE(tree.occluded(
                r, [](std::uint32_t, const Rayf&) { return true; }, st));
            CHECK(st.prims == 0);
        }
    }
}

TEST_CASE("kd-tree rejects invalid rays before touching a node", "[accel][kdtree]") {
    const test::Soup soup = test::random_soup(test::SoupKind::boxes, 3, 100);
    const KdTree tree = build_kd("kdtree:sah", soup.input());
    test::check_rejects_invalid_rays(tree, soup);
}

TEST_CASE("SAH kd-tree beats the median kd-tree and brute force on counts", "[accel][kdtree]") {
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 11, 500);
    const std::vector<Rayf> rays = test::random_rays(soup, 11, 400);
    const auto count = [&](const auto& accel) {
        return test::closest_hit_stats(accel, soup, rays);
    };
    const KdTree sah = build_kd("kdtree:sah", soup.input());
    const KdTree median = build_kd("kdtree:median", soup.input());
    const TraversalStats brute = count(BruteForce::build(soup.input()));
    const TraversalStats st_sah = count(sah);
    const TraversalStats st_median = count(median);
    CHECK(st_sah.rays == brute.rays);
    // Brute force makes one box test per primitive per ray; the SAH tree far fewer of each.
    CHECK(st_sah.prims * 10 < brute.nodes);
    CHECK(st_sah.nodes * 4 < brute.nodes);
    CHECK(sah.info().sah_cost < median.info().sah_cost);
    CHECK(st_sah.prims < st_median.prims);
}

TEST_CASE("kd-tree figures on a 10,000-primitive soup", "[.report][kdtree]") {
    for (const auto kind : {test::SoupKind::triangles, test::SoupKind::boxes}) {
        const test::Soup soup = test::random_soup(kind, 42, 10000);
        const std::vector<Rayf> rays = test::random_rays(soup, 42, 20000);
        for (const std::string& builder : kd_rows) {
            const KdTree tree = build_kd(builder, soup.input());
            const TraversalStats st = test::closest_hit_stats(tree, soup, rays);
            const AccelInfo info = tree.info();
            std::printf(
                "%s %s: nodes/ray %.2f prims/ray %.2f nodes %llu depth %u "
                "refs/prim %.2f sah %.2f\n",
                builder.c_str(), kind == test::SoupKind::boxes ? "boxes" : "triangles",
                static_cast<double>(st.nodes) / static_cast<double>(st.rays),
                static_cast<double>(st.prims) / static_cast<double>(st.rays),
                static_cast<unsigned long long>(info.nodes), info.max_depth, info.refs_per_prim,
                info.sah_cost);
            CHECK(tree.validate().empty());
        }
    }
}

}  // namespace rtlab
