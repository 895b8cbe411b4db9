// Certified ray/triangle hits (intersect/triangle/exact_hit.h) against CGAL's exact kernel as an
// independent oracle (crosscheck/exact_triangle_oracle.h, which keeps CGAL inside the crosscheck
// library): hit or miss, t the nearest float to the exact t, and the closest primitive under the
// lowest-id tie rule, on random rays, rays aimed exactly at lattice vertices and shared edges at
// three scales, a perturbed closed sphere, grazing and coplanar rays, axis-aligned rays and
// origins on the surface. The plain watertight float test is scored on the same rays.

#include "intersect/triangle/exact_hit.h"

#include "crosscheck/exact_triangle_oracle.h"
#include "intersect/triangle/watertight.h"
#include "support/exact_ray_sets.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace rtlab;
using rtlab::test::RaySet;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

/// True when f is the float nearest to the oracle's exact t (ties to even). The oracle rounds its
/// exact t itself, and the nearest float is unique, so this is float equality; a non-finite f is
/// never right.
bool is_nearest(float f, float oracle_t) {
    return std::isfinite(f) && f == oracle_t;
}

/// Agreement counts for one set: the certified test must have no disagreement; the plain
/// watertight float test's errors are only reported.
struct Score {
    std::size_t rays = 0, pairs = 0, fallbacks = 0;
    std::size_t pair_errors = 0, closest_errors = 0;    // certified test vs the oracle
    std::size_t wt_pair_errors = 0, wt_hit_errors = 0;  // watertight: per pair; closest hit/miss
    std::size_t wt_prim_errors = 0, wt_t_errors = 0;    // watertight: closest prim; t not nearest
    std::string first_error;
};

/// The closest hit of each kind for one ray, brute force over the set.
struct Closest {
    std::uint32_t oracle_id = invalid_id, exact_id = invalid_id, wt_id = invalid_id;
    float oracle_t = inf;  ///< the oracle's closest t, rounded to nearest
    ExactHit exact;
    float wt_t = inf;
};

void note(Score& s, const RaySet& set, std::size_t ray, std::uint32_t prim, const char* what) {
    if (s.first_error.empty()) {
        std::ostringstream os;
        os << set.name << ": ray " << ray << " prim " << prim << ": " << what;
        s.first_error = os.str();
    }
}

/// Tests one ray against every triangle of the set, pair by pair and for the closest hit.
void score_ray(const RaySet& set, std::size_t i, Score& s) {
    using Wt = Watertight<float>;
    const Rayf& ray = set.rays[i];
    const xcheck::ExactTriangleHits oracle = xcheck::exact_triangle_hits(set.tris, ray);
    const Wt::RayData wrd = Wt::precompute(ray);
    Closest c;
    c.oracle_id = oracle.closest;
    if (c.oracle_id != invalid_id) {
        c.oracle_t = oracle.pairs[c.oracle_id].t;
    }
    for (std::uint32_t id = 0; id < set.tris.size(); ++id) {
        const Trianglef& tri = set.tris[id];
        const xcheck::ExactPairHit& o = oracle.pairs[id];
        const ExactHit h = exact_intersect(ray, tri.p0, tri.p1, tri.p2);
        const auto w = Wt::intersect(Wt::prepare(tri), ray, wrd);
        ++s.pairs;
        s.fallbacks += h.fallback ? 1 : 0;
        if (h.hit != o.hit || (o.hit && !is_nearest(h.t, o.t))) {
            ++s.pair_errors;
            note(s, set, i, id, h.hit != o.hit ? "hit/miss" : "t not nearest");
        }
        if (w.has_value() != o.hit || (o.hit && !is_nearest(w->t, o.t))) {
            ++s.wt_pair_errors;
        }
        if (h.hit && (c.exact_id == invalid_id ||
                      exact_less(ray, h, tri, id, c.exact, set.tris[c.exact_id], c.exact_id))) {
            c.exact_id = id;
            c.exact = h;
        }
        if (w && w->t < c.wt_t) {
            c.wt_id = id;
            c.wt_t = w->t;
        }
    }
    if (c.exact_id != c.oracle_id) {
        ++s.closest_errors;
        note(s, set, i, c.exact_id, "closest primitive");
    }
    const bool oracle_hit = c.oracle_id != invalid_id;
    s.wt_hit_errors += (c.wt_id != invalid_id) != oracle_hit ? 1 : 0;
    s.wt_prim_errors += oracle_hit && c.wt_id != invalid_id && c.wt_id != c.oracle_id ? 1 : 0;
    s.wt_t_errors += oracle_hit && c.wt_id != invalid_id && !is_nearest(c.wt_t, c.oracle_t) ? 1 : 0;
}

/// Scores a whole set, reports its counts once and requires full agreement.
void check_set(const RaySet& set) {
    Score s;
    s.rays = set.rays.size();
    for (std::size_t i = 0; i < set.rays.size(); ++i) {
        score_ray(set, i, s);
    }
    INFO(set.name << ": " << s.rays << " rays, " << s.pairs << " pairs, " << s.fallbacks
                  << " exact fallbacks; watertight float: " << s.wt_pair_errors
                  << " pairs wrong, closest " << s.wt_hit_errors << " hit/miss, "
                  << s.wt_prim_errors << " primitive, " << s.wt_t_errors << " t not nearest");
    INFO(s.first_error);
    CHECK(s.rays > 0);
    CHECK(s.pair_errors == 0);
    CHECK(s.closest_errors == 0);
}

}  // namespace

TEST_CASE("certified hits agree with CGAL on every adversarial ray set", "[exact]") {
    for (const RaySet& set : test::exact_ray_sets()) {
        check_set(set);
    }
}

TEST_CASE("certified hits round t to nearest and break exact ties by the lowest id", "[exact]") {
    // Two triangles sharing the edge x = 1 of the plane z = 3; a ray down onto that edge.
    const Trianglef a{{0, 0, 3}, {1, 0, 3}, {1, 1, 3}}, b{{1, 0, 3}, {2, 0, 3}, {1, 1, 3}};
    const Rayf ray{{1, 0.5f, 0}, {0, 0, 1}, 0.0f, inf};
    const ExactHit ha = exact_intersect(ray, a.p0, a.p1, a.p2);
    const ExactHit hb = exact_intersect(ray, b.p0, b.p1, b.p2);
    REQUIRE(ha.hit);
    REQUIRE(hb.hit);
    CHECK(ha.t == 3.0f);
    CHECK(hb.t == 3.0f);
    CHECK(exact_less(ray, ha, a, 4, hb, b, 7));
    CHECK_FALSE(exact_less(ray, hb, b, 7, ha, a, 4));
    CHECK(exact_less(ray, hb, b, 2, ha, a, 4));
    // t = 1/3 exactly: the nearest float, not a truncation.
    const Rayf third{{0.25f, 0.25f, 0}, {0, 0, 9}, 0.0f, inf};
    const ExactHit h3 = exact_intersect(third, a.p0, a.p1, a.p2);
    REQUIRE(h3.hit);
    CHECK(h3.t == 1.0f / 3.0f);
}

TEST_CASE("certified hits order distinct exact t that round to one float", "[exact]") {
    // Planes z = 3 and z = 3 + 2^-22 seen from z = -2^-22 along (0, 0, 3): t = 1 + 2^-22 / 3 and
    // 1 + 2^-21 / 3 both round to 1 + 2^-23, so only the exact comparison orders them.
    const float h = 3.0f + 0x1.0p-22f;
    const Trianglef near{{0, 0, 3}, {1, 0, 3}, {0, 1, 3}}, far{{0, 0, h}, {1, 0, h}, {0, 1, h}};
    const Rayf ray{{0.25f, 0.25f, -0x1.0p-22f}, {0, 0, 3}, 0.0f, inf};
    const ExactHit hn = exact_intersect(ray, near.p0, near.p1, near.p2);
    const ExactHit hf = exact_intersect(ray, far.p0, far.p1, far.p2);
    REQUIRE(hn.hit);
    REQUIRE(hf.hit);
    CHECK(hn.t == hf.t);
    CHECK(exact_less(ray, hn, near, 9, hf, far, 1));  // smaller t wins over the lower id
    CHECK_FALSE(exact_less(ray, hf, far, 1, hn, near, 9));
    CHECK(exact_compare_t(ray, near, far) == -1);
    CHECK(exact_compare_t(ray, far, far) == 0);
}

TEST_CASE("certified hits round t at and next to a midpoint between floats", "[exact]") {
    // Plane z = 3 + 2^-22, dir (0, 0, 3): t = (3 + 2^-22 - oz) / 3. With oz = 2^-24, t is exactly
    // 1 + 2^-24, halfway between 1 and 1 + 2^-23 (ties to even: 1); one float of oz either way
    // moves t just above or below the midpoint.
    const float h = 3.0f + 0x1.0p-22f;
    const Trianglef tri{{0, 0, h}, {1, 0, h}, {0, 1, h}};
    const auto t_for = [&](float oz) {
        const ExactHit hit =
            exact_intersect({{0.25f, 0.25f, oz}, {0, 0, 3}, 0.0f, inf}, tri.p0, tri.p1, tri.p2);
        REQUIRE(hit.hit);
        return hit;
    };
    const ExactHit mid = t_for(0x1.0p-24f);
    CHECK(mid.t == 1.0f);
    CHECK(mid.fallback);  // a tie cannot be certified by the double enclosure
    CHECK(t_for(std::nextafter(0x1.0p-24f, 0.0f)).t == 1.0f + 0x1.0p-23f);
    CHECK(t_for(std::nextafter(0x1.0p-24f, 1.0f)).t == 1.0f);
}
