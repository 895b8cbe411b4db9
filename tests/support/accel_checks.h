#pragma once
// Catch2 checks shared by the acceleration-structure tests: agreement of one structure with the
// brute-force oracle on a ray set (one rule for every test), and the rejection of a ray by both
// queries.

#include "accel/any_accel.h"
#include "accel/brute_force.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtlab::test {

/// True when registry row e declares parameter `key`.
inline bool declares(const AccelEntry& e, std::string_view key) {
    return std::any_of(e.params.begin(), e.params.end(),
                       [&](const ParamSpec& p) { return p.key == key; });
}

/// `row` followed by ",key=value" for each entry of `settings` ("key=value,key=value...") whose key
/// registry row `row` declares and which takes effect with the other settings: one set of tree
/// settings spelled the same way for rows with and without, say, SAH costs, or for a layout row
/// built from any source builder (`from=lbvh` leaves out ct, bins, ...).
inline std::string spec_with(const std::string& row, std::string_view settings) {
    const AccelEntry* e = find_accel(row);
    REQUIRE(e != nullptr);
    AccelSpec s = default_spec(*e);
    std::vector<std::pair<std::size_t, std::string_view>> given;  // parameter index, key=value
    while (!settings.empty()) {
        const std::size_t comma = settings.find(',');
        const std::string_view kv = settings.substr(0, comma);
        settings = comma == std::string_view::npos ? "" : settings.substr(comma + 1);
        const std::size_t eq = kv.find('=');
        for (std::size_t i = 0; i < e->params.size(); ++i) {
            if (e->params[i].key == kv.substr(0, eq)) {
                s.values[i] = e->params[i].parse(row, kv.substr(eq + 1));
                given.emplace_back(i, kv);
            }
        }
    }
    std::string out = row;
    for (const auto& [i, kv] : given) {
        if (s.applies(i)) {
            out += ",";
            out += kv;
        }
    }
    return out;
}

/// Specs of row e: its defaults, and for each parameter one spec with only that parameter moved
/// to an extreme of its range (the minimum, or the maximum where the minimum is the default).
inline std::vector<AccelSpec> default_and_varied_specs(const AccelEntry& e) {
    std::vector<AccelSpec> out{default_spec(e)};
    for (std::size_t i = 0; i < e.params.size(); ++i) {
        const ParamSpec& p = e.params[i];
        AccelSpec s = default_spec(e);
        if (p.kind == ParamKind::choice) {
            s.values[i] = p.default_value == 0 ? 1 : 0;
        } else {
            s.values[i] = p.min != p.default_value ? p.min : p.max;
        }
        out.push_back(s);
    }
    return out;
}

/// Every row of the registry with default_and_varied_specs, brute force first.
inline std::vector<AccelSpec> registry_specs() {
    std::vector<AccelSpec> out;
    for (const AccelEntry& e : accel_registry()) {
        for (AccelSpec& s : default_and_varied_specs(e)) {
            out.push_back(std::move(s));
        }
    }
    return out;
}

/// The brute-force oracle's answer for one ray.
struct OracleAnswer {
    Hit hit;                ///< closest hit (prim == invalid_id: a miss)
    bool occluded = false;  ///< any-hit answer
};

/// The oracle's answers for every ray, computed once for all the structures checked against them.
inline std::vector<OracleAnswer> oracle_answers(const Soup& soup, const std::vector<Rayf>& rays) {
    const BruteForce oracle = BruteForce::build(soup.input());
    std::vector<OracleAnswer> out(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        Rayf r = rays[i];
        oracle.intersect(r, soup.closest_hit(out[i].hit));
        out[i].occluded = oracle.occluded(rays[i], soup.any_hit());
    }
    return out;
}

/// Checks that got, a closest hit of ray, is the oracle's closest hit want (which hits): the same
/// t up to rounding of equal distances, on want's primitive or on one at an exact tie (re-tested).
inline void check_same_closest_hit(const Soup& soup,
                                   const Rayf& ray,
                                   const Hit& want,
                                   const Hit& got) {
    CHECK(got.t == Approx(want.t).epsilon(1e-6));
    if (got.prim != want.prim) {
        const auto again = soup.hit(got.prim, ray);
        REQUIRE(again.has_value());
        CHECK(again->t == want.t);  // an exact tie
    }
}

/// Checks accel against the oracle's answers `expected` (oracle_answers(soup, rays)) on every
/// ray, with plain and robust traversal alike: the oracle's hit or miss, its closest hit
/// (check_same_closest_hit) and its occlusion; robust's closest hit is never farther than plain's.
/// Plain traversal is held to the oracle too: it can lose a triangle hit on a box face that its
/// unpadded slab test rounds to a miss (the stability suite counts such rays on edge-aimed sets),
/// but every registry row meets the rule on random_rays, rays from primitive box faces included.
template <class A>
void check_agrees_with_oracle(const A& accel,
                              const Soup& soup,
                              const std::vector<Rayf>& rays,
                              const std::vector<OracleAnswer>& expected) {
    REQUIRE(expected.size() == rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Rayf& ray = rays[i];
        CAPTURE(i, ray.org.x, ray.org.y, ray.org.z, ray.dir.x, ray.dir.y, ray.dir.z, ray.tmin,
                ray.tmax);
        const Hit& want = expected[i].hit;
        CHECK(expected[i].occluded == want.valid());  // the oracle's two queries agree

        Hit robust, normal;
        Rayf rr = ray, rn = ray;
        const bool robust_hit = accel.template intersect<true>(rr, soup.closest_hit(robust));
        const bool normal_hit = accel.intersect(rn, soup.closest_hit(normal));
        REQUIRE(robust_hit == want.valid());
        REQUIRE(normal_hit == want.valid());
        if (want.valid()) {
            REQUIRE(robust.t <= normal.t);
            check_same_closest_hit(soup, ray, want, robust);
            check_same_closest_hit(soup, ray, want, normal);
        }
        CHECK(accel.template occluded<true>(ray, soup.any_hit()) == expected[i].occluded);
        CHECK(accel.occluded(ray, soup.any_hit()) == expected[i].occluded);
    }
}

/// check_agrees_with_oracle with the oracle's answers for rays.
template <class A>
void check_agrees_with_brute_force(const A& accel,
                                   const Soup& soup,
                                   const std::vector<Rayf>& rays) {
    check_agrees_with_oracle(accel, soup, rays, oracle_answers(soup, rays));
}

/// Checks that neither the closest-hit nor the any-hit query of ray reports a hit on accel, and
/// returns the counters of both queries (for the caller's checks on nodes, rays or prims).
template <class A>
TraversalStats check_no_hit(const A& accel, const Soup& soup, const Rayf& ray) {
    TraversalStats st;
    Hit h;
    Rayf r = ray;
    CHECK_FALSE(accel.intersect(r, soup.closest_hit(h), st));
    CHECK_FALSE(accel.occluded(ray, soup.any_hit(), st));
    return st;
}

/// Checks that accel rejects a ray with a NaN origin, one with a zero direction and one with an
/// empty window (tmin > tmax): no hit, no node visited and no ray counted.
template <class A>
void check_rejects_invalid_rays(const A& accel, const Soup& soup) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const Rayf& ray : {Rayf{{nan, 0, 0}, {1, 0, 0}}, Rayf{{0, 0, 0}, {0, 0, 0}},
                            Rayf{{0, 0, 0}, {1, 0, 0}, 2, 1}}) {
        const TraversalStats st = check_no_hit(accel, soup, ray);
        CHECK(st.nodes == 0);
        CHECK(st.rays == 0);
    }
}

}  // namespace rtlab::test
