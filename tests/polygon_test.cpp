// Ray-polygon methods (crossing count, winding number): analytic hits, concave notches, the
// half-open vertex rule, a self-intersecting star, windows, parallel rays, all three projections.
#include "intersect/polygon/methods.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace rtlab;

namespace {

/// The polygon with 2D outline pts placed in the plane `axis` = c (the other two axes in order
/// u = axis + 1, v = axis + 2), so its normal is along `axis`.
template <class T>
Polygon<T> planar(const std::vector<std::array<T, 2>>& pts, std::size_t axis, T c) {
    Polygon<T> p;
    for (const auto& q : pts) {
        Vec3<T> v;
        v[axis] = c;
        v[(axis + 1) % 3] = q[0];
        v[(axis + 2) % 3] = q[1];
        p.vertices.push_back(v);
    }
    return p;
}

/// A ray from height 5 above (u, v) straight down onto the plane axis = 0.
template <class T>
Ray<T> down_ray(T u, T v, std::size_t axis) {
    Ray<T> r;
    r.org[axis] = T(5);
    r.org[(axis + 1) % 3] = u;
    r.org[(axis + 2) % 3] = v;
    r.dir[axis] = T(-1);
    return r;
}

/// Calls f.template operator()<M>() for both polygon methods in both precisions.
template <class F>
void for_all(F&& f) {
    for_each_polygon_method<float>(f);
    for_each_polygon_method<double>(f);
}

template <class T>
std::vector<std::array<T, 2>> square() {
    return {{T(0), T(0)}, {T(1), T(0)}, {T(1), T(1)}, {T(0), T(1)}};
}

/// L shape: the unit square [0, 2]^2 minus the notch [1, 2] x [1, 2].
template <class T>
std::vector<std::array<T, 2>> l_shape() {
    return {{T(0), T(0)}, {T(2), T(0)}, {T(2), T(1)}, {T(1), T(1)}, {T(1), T(2)}, {T(0), T(2)}};
}

/// Pentagram traced through every second vertex of a regular pentagon: self-intersecting, the
/// central pentagon has winding number 2.
template <class T>
std::vector<std::array<T, 2>> pentagram() {
    std::vector<std::array<T, 2>> pts;
    for (int i = 0; i < 5; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * (2 * i) / 5.0 + 1.5707963267948966;
        pts.push_back({static_cast<T>(std::cos(a)), static_cast<T>(std::sin(a))});
    }
    return pts;
}

}  // namespace

TEST_CASE("polygon methods hit squares, triangles and L shapes at the analytic t",
          "[intersect][polygon]") {
    for_all([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        for (std::size_t axis = 0; axis < 3; ++axis) {
            CAPTURE(axis);
            const auto sq = M::prepare(planar<T>(square<T>(), axis, T(0)));
            const auto h = M::intersect(sq, down_ray<T>(T(0.5), T(0.25), axis));
            REQUIRE(h);
            CHECK(h->t == T(5));
            CHECK_FALSE(M::intersect(sq, down_ray<T>(T(1.5), T(0.5), axis)));
            CHECK_FALSE(M::intersect(sq, down_ray<T>(T(-0.1), T(0.5), axis)));

            const auto tri =
                M::prepare(planar<T>({{T(0), T(0)}, {T(2), T(0)}, {T(0), T(2)}}, axis, T(0)));
            CHECK(M::intersect(tri, down_ray<T>(T(0.9), T(0.9), axis)));
            CHECK_FALSE(M::intersect(tri, down_ray<T>(T(1.1), T(1.1), axis)));

            // Concave: the notch of the L misses, both arms hit.
            const auto l = M::prepare(planar<T>(l_shape<T>(), axis, T(0)));
            CHECK(M::intersect(l, down_ray<T>(T(1.5), T(0.5), axis)));
            CHECK(M::intersect(l, down_ray<T>(T(0.5), T(1.5), axis)));
            CHECK_FALSE(M::intersect(l, down_ray<T>(T(1.5), T(1.5), axis)));
            const Bounds3<T> b = M::bounds(l);
            CHECK(b.lo[axis] == T(0));
            CHECK(b.hi[axis] == T(0));
            CHECK(b.hi[(axis + 1) % 3] == T(2));
        }
    });
}

TEST_CASE("polygon methods: tilted plane, either orientation, t from a non-unit direction",
          "[intersect][polygon]") {
    for_all([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        // Square in the plane z = x (normal (-1, 0, 1)); dominant axis tie broken to x.
        Polygon<T> p{
            {{T(0), T(0), T(0)}, {T(1), T(0), T(1)}, {T(1), T(1), T(1)}, {T(0), T(1), T(0)}}};
        for (int flip = 0; flip < 2; ++flip) {
            const auto pp = M::prepare(p);
            const Ray<T> r{{T(0.5), T(0.5), T(3)}, {T(0), T(0), T(-2)}};
            const auto h = M::intersect(pp, r);
            REQUIRE(h);
            CHECK(h->t == Approx(1.25).epsilon(1e-6));
            CHECK_FALSE(M::intersect(pp, Ray<T>{{T(1.5), T(0.5), T(3)}, {T(0), T(0), T(-2)}}));
            std::reverse(p.vertices.begin(), p.vertices.end());
        }
    });
}

TEST_CASE("polygon methods honour [tmin, tmax] and miss parallel rays without NaN",
          "[intersect][polygon]") {
    for_all([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        const auto sq = M::prepare(planar<T>(square<T>(), 2, T(0)));
        Ray<T> r = down_ray<T>(T(0.5), T(0.5), 2);
        r.tmax = T(4.999);
        CHECK_FALSE(M::intersect(sq, r));
        r.tmax = T(5);
        CHECK(M::intersect(sq, r));  // closed window
        r.tmin = T(5.001);
        r.tmax = std::numeric_limits<T>::infinity();
        CHECK_FALSE(M::intersect(sq, r));
        CHECK_FALSE(M::occluded(sq, r));
        // Behind the origin.
        CHECK_FALSE(M::intersect(sq, Ray<T>{{T(0.5), T(0.5), T(-1)}, {T(0), T(0), T(-1)}}));
        // Parallel: above the plane and lying in it (both miss, dot(n, d) == 0).
        CHECK_FALSE(M::intersect(sq, Ray<T>{{T(-1), T(0.5), T(1)}, {T(1), T(0), T(0)}}));
        CHECK_FALSE(M::intersect(sq, Ray<T>{{T(-1), T(0.5), T(0)}, {T(1), T(0), T(0)}}));
        CHECK_FALSE(M::intersect(sq, Ray<T>{{T(-1), T(0.5), T(0)}, {T(1), T(-0.0), T(-0.0)}}));
        // Degenerate polygons never hit.
        const auto two = M::prepare(Polygon<T>{{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}}});
        CHECK_FALSE(M::intersect(two, down_ray<T>(T(0.5), T(0), 2)));
        const auto line =
            M::prepare(Polygon<T>{{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}, {T(2), T(0), T(0)}}});
        CHECK_FALSE(M::intersect(line, down_ray<T>(T(1), T(0), 2)));
    });
}

TEST_CASE("polygon methods: shared edges and vertices are counted exactly once",
          "[intersect][polygon]") {
    for_all([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        // Four unit squares around the origin share edges on the axes and the vertex (0, 0).
        std::vector<typename M::Prepared> quads;
        for (int qx = -1; qx <= 0; ++qx) {
            for (int qy = -1; qy <= 0; ++qy) {
                const T x0 = static_cast<T>(qx), y0 = static_cast<T>(qy);
                quads.push_back(M::prepare(
                    planar<T>({{x0, y0}, {x0 + 1, y0}, {x0 + 1, y0 + 1}, {x0, y0 + 1}}, 2, T(0))));
            }
        }
        const T pts[][2] = {{0, 0},       {0, T(0.5)},  {T(0.5), 0}, {0, T(-0.5)},
                            {T(-0.5), 0}, {T(0.25), 1}, {1, 1},      {T(-1), T(0.5)}};
        for (const auto& q : pts) {
            CAPTURE(q[0], q[1]);
            int hits = 0;
            for (const auto& p : quads) {
                hits += M::intersect(p, down_ray<T>(q[0], q[1], 2)).has_value() ? 1 : 0;
            }
            // Points on the outer boundary (last three) belong to at most one square.
            const bool interior = std::abs(q[0]) < 1 && std::abs(q[1]) < 1;
            if (interior) {
                CHECK(hits == 1);
            } else {
                CHECK(hits <= 1);
            }
        }
        // The test ray through a vertex (v = 0 at a vertex of a diamond) is not double-counted.
        const auto diamond = M::prepare(
            planar<T>({{T(0), T(-1)}, {T(1), T(0)}, {T(0), T(1)}, {T(-1), T(0)}}, 2, T(0)));
        CHECK(M::intersect(diamond, down_ray<T>(T(-0.5), T(0), 2)));
        CHECK(M::intersect(diamond, down_ray<T>(T(0.5), T(0), 2)));
        CHECK_FALSE(M::intersect(diamond, down_ray<T>(T(-1.5), T(0), 2)));
        CHECK_FALSE(M::intersect(diamond, down_ray<T>(T(1.5), T(0), 2)));
        // A comb's test ray passing through several vertices at once.
        const auto comb = M::prepare(planar<T>({{T(0), T(0)},
                                                {T(5), T(0)},
                                                {T(5), T(2)},
                                                {T(4), T(2)},
                                                {T(4), T(1)},
                                                {T(3), T(1)},
                                                {T(3), T(2)},
                                                {T(2), T(2)},
                                                {T(2), T(1)},
                                                {T(1), T(1)},
                                                {T(1), T(2)},
                                                {T(0), T(2)}},
                                               2, T(0)));
        CHECK(M::intersect(comb, down_ray<T>(T(0.5), T(1), 2)));
        CHECK_FALSE(M::intersect(comb, down_ray<T>(T(1.5), T(1.5), 2)));
        CHECK(M::intersect(comb, down_ray<T>(T(2.5), T(1.5), 2)));
        CHECK(M::intersect(comb, down_ray<T>(T(4.5), T(0.5), 2)));
    });
}

TEST_CASE("self-intersecting pentagram: even-odd leaves the centre out, nonzero keeps it",
          "[intersect][polygon]") {
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const Polygon<double> star = planar<double>(pentagram<double>(), axis, 0.5);
        const auto pc = PolygonCrossing<double>::prepare(star);
        const auto pw = PolygonWinding<double>::prepare(star);
        const Ray<double> centre = down_ray<double>(0.0, 0.05, axis);
        CHECK_FALSE(PolygonCrossing<double>::intersect(pc, centre));
        REQUIRE(PolygonWinding<double>::intersect(pw, centre));
        CHECK(std::abs(PolygonWinding<double>::winding(pw, 0.0, 0.05)) == 2);
        // A tip of the star (winding 1): both hit. Outside: both miss.
        const Ray<double> tip = down_ray<double>(0.0, 0.8, axis);
        CHECK(PolygonCrossing<double>::intersect(pc, tip));
        CHECK(PolygonWinding<double>::intersect(pw, tip));
        const Ray<double> out = down_ray<double>(0.7, 0.7, axis);
        CHECK_FALSE(PolygonCrossing<double>::intersect(pc, out));
        CHECK_FALSE(PolygonWinding<double>::intersect(pw, out));
    }
}

TEST_CASE("crossing count and winding number agree on random simple polygons",
          "[intersect][polygon]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int k = 0; k < 50; ++k) {
        // Star-shaped (simple) polygon with 3 to 16 vertices.
        const int n = 3 + k % 14;
        std::vector<std::array<double, 2>> pts;
        for (int i = 0; i < n; ++i) {
            const double a = 6.283185307179586 * (i + 0.4 * uni(rng)) / n;
            const double r = 0.6 + 0.4 * uni(rng);
            pts.push_back({r * std::cos(a), r * std::sin(a)});
        }
        const auto poly = planar<double>(pts, static_cast<std::size_t>(k % 3), 0.0);
        const auto pc = PolygonCrossing<double>::prepare(poly);
        const auto pw = PolygonWinding<double>::prepare(poly);
        for (int j = 0; j < 200; ++j) {
            const Ray<double> r =
                down_ray<double>(uni(rng), uni(rng), static_cast<std::size_t>(k % 3));
            CHECK(PolygonCrossing<double>::intersect(pc, r).has_value() ==
                  PolygonWinding<double>::intersect(pw, r).has_value());
        }
    }
}
