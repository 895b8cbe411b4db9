// Sphere and implicit-surface methods against the exact oracles of crosscheck/ (CGAL Epeck, GMP
// rationals, MPFR, Sturm sequences). Bounds below were measured with seed 1 at 20,000 and
// 100,000 rays (g++ 12, x86-64, Debug) and are set with a margin; each says why.
#include "crosscheck/checks.h"
#include "support/oracle_rays.h"
#include "support/oracle_rows.h"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace rtlab;

namespace {

using rtlab::test::find_row;

double wrong_rate(const xcheck::Row& r) {
    return static_cast<double>(r.false_hit + r.false_miss) / static_cast<double>(r.rays);
}

/// Same rows apart from the timing column.
bool same_answers(const std::vector<xcheck::Row>& a, const std::vector<xcheck::Row>& b) {
    if (a.size() != b.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].method != b[i].method || a[i].set != b[i].set || a[i].agree != b[i].agree ||
            a[i].false_hit != b[i].false_hit || a[i].max_rel_t_err != b[i].max_rel_t_err ||
            a[i].median_rel_t_err != b[i].median_rel_t_err) {
            return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("sphere methods against the exact oracle", "[intersect][sphere][oracle]") {
    xcheck::Options opt;
    opt.rays = test::oracle_rays();
    opt.by_set = true;
    const std::vector<xcheck::Row> rows = xcheck::check_spheres(opt);
    const std::vector<std::string> sets{"random",  "centre", "grazing",  "inside",
                                        "surface", "axis",   "far_small"};
    for (const std::string& set : sets) {
        CAPTURE(set);
        // Double: every method is exact in hit/miss on every set, including grazing rays 1e-7 r
        // off tangency (double resolves ~1e-8 relative). Measured max t error: 7.8e-13 (stable,
        // grazing), 1.5e-11 (algebraic, far_small), 1.6e-9 (stable, surface: t ~ 1e-4 is tiny,
        // and the chord comes from r^2 - |f_perp|^2 with absolute error eps r^2).
        for (const char* m : {"geometric", "algebraic", "stable"}) {
            CAPTURE(m);
            const xcheck::Row& r = find_row(rows, m, "double", set);
            CHECK(r.false_hit == 0);
            CHECK(r.false_miss == 0);
            CHECK(r.max_rel_t_err < (set == "surface" ? 1e-7 : 1e-9));
        }
        // Float, stable: exact answers everywhere but the tangency band, i.e. the grazing set
        // (rays |delta| = 1e-7 .. 1e-2 r off tangency; float resolves ~1e-4). Measured max t
        // error <= 8.6e-7 (~7 ulps) away from grazing/surface; bound 4e-6.
        const xcheck::Row& s = find_row(rows, "stable", "float", set);
        if (set != "grazing") {
            CHECK(s.false_hit == 0);
            CHECK(s.false_miss == 0);
        }
        if (set != "grazing" && set != "surface") {
            CHECK(s.max_rel_t_err < 4e-6);
        }
    }
    // Float grazing band: measured 2.3% wrong answers (stable) and 18% (geometric, algebraic:
    // b^2 - ac cancels). Bounds 4% and "stable at least 4x better".
    const xcheck::Row& sg = find_row(rows, "stable", "float", "grazing");
    const xcheck::Row& ag = find_row(rows, "algebraic", "float", "grazing");
    CHECK(wrong_rate(sg) < 0.04);
    CHECK(wrong_rate(ag) > 4 * wrong_rate(sg));
    // Small far spheres (D/r up to 1e4): measured 6.5% wrong for algebraic and geometric in
    // float, none for stable.
    CHECK(wrong_rate(find_row(rows, "algebraic", "float", "far_small")) > 0.02);
    CHECK(wrong_rate(find_row(rows, "geometric", "float", "far_small")) > 0.02);
    CHECK(find_row(rows, "stable", "float", "all").median_rel_t_err < 1e-7);  // measured 4.8e-8
}

TEST_CASE("sphere cross-check is deterministic for a fixed seed", "[intersect][sphere][oracle]") {
    xcheck::Options opt;
    opt.rays = 1400;
    opt.seed = 7;
    opt.by_set = true;
    CHECK(same_answers(xcheck::check_spheres(opt), xcheck::check_spheres(opt)));
    opt.rays = 300;
    opt.methods = {"torus/closed_form", "tangle/newton"};
    CHECK(same_answers(xcheck::check_implicits(opt), xcheck::check_implicits(opt)));
}

namespace {

/// Bounds for the implicit rows (surface/method x precision x set).
void check_implicit_rows(const std::vector<xcheck::Row>& rows) {
    for (const char* surface : {"torus", "tangle"}) {
        for (const char* m : {"closed_form", "newton", "laguerre"}) {
            const std::string name = std::string(surface) + "/" + m;
            CAPTURE(name);
            for (const char* set : {"random", "grazing", "axis"}) {
                CAPTURE(set);
                // Double: exact hit/miss on every set (grazing rays are >= 1e-7 box sizes off
                // tangency). Measured max t error 2.9e-12 except Newton on grazing rays, which
                // may return a later root when a root pair and two extrema share one of its 16
                // steps (measured 4.9e-2); bound 1e-10 elsewhere.
                const xcheck::Row& d = find_row(rows, name, "double", set);
                CHECK(d.false_hit == 0);
                CHECK(d.false_miss == 0);
                if (std::string(m) != "newton" || std::string(set) != "grazing") {
                    CHECK(d.max_rel_t_err < 1e-10);
                }
                // Float: measured <= 2.2% wrong answers on grazing rays, <= 0.003% (1 ray of
                // 33,334) on random rays, none on axis rays; bounds 4% and 0.5% (one ray in a
                // 667-ray set is 0.15%).
                const xcheck::Row& f = find_row(rows, name, "float", set);
                CHECK(wrong_rate(f) < (std::string(set) == "grazing" ? 0.04 : 0.005));
            }
            // Float t: median measured <= 1e-7; random-set max <= 1.7e-5 (bound 1e-4).
            CHECK(find_row(rows, name, "float", "all").median_rel_t_err < 4e-7);
            CHECK(find_row(rows, name, "float", "random").max_rel_t_err < 1e-4);
        }
    }
}

}  // namespace

TEST_CASE("implicit methods against the exact oracle", "[intersect][implicit][oracle]") {
    // A tenth of the oracle ray count: Laguerre costs ~0.1 ms per ray in a Debug build, and the
    // Sturm/MPFR oracle ~0.2 ms; the [.slow] case below runs the full count.
    xcheck::Options opt;
    opt.rays = std::max<std::size_t>(test::oracle_rays() / 10, 300);
    opt.by_set = true;
    check_implicit_rows(xcheck::check_implicits(opt));
}

TEST_CASE("implicit methods against the exact oracle, full ray count",
          "[intersect][implicit][oracle][.slow]") {
    xcheck::Options opt;
    opt.rays = test::oracle_rays();
    opt.by_set = true;
    check_implicit_rows(xcheck::check_implicits(opt));
}
