// Triangle intersection methods: analytic hits, misses, the ray window, back faces, axis-aligned
// and denormal directions, edges, degenerate triangles, agreement between methods, and pbrt-style
// watertightness on a closed perturbed sphere mesh.
#include "intersect/triangle/methods.h"
#include "intersect/triangle/sphere_mesh.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

using namespace rtlab;

namespace {

/// Seeded uniform numbers in double (converted to the method's scalar where used).
struct Rng {
    std::mt19937_64 gen;
    explicit Rng(std::uint64_t seed) : gen(seed) {}
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(gen() >> 11) * 0x1.0p-53;
    }
    Vec3d vec(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
    Vec3d unit() {
        for (;;) {
            const Vec3d p = vec(-1, 1);
            const double l2 = length_squared(p);
            if (l2 > 1e-4 && l2 <= 1) {
                return p / std::sqrt(l2);
            }
        }
    }
};

/// Relative tolerance for analytic comparisons in scalar T.
template <class T>
constexpr double tol() {
    return std::is_same_v<T, float> ? 1e-4 : 1e-10;
}

/// The method's answer as an optional hit; occlusion-only methods report t = NaN on a hit.
template <class M>
std::optional<PrimHit<typename M::Scalar>> probe(const typename M::Prepared& p,
                                                 const Ray<typename M::Scalar>& r) {
    using T = typename M::Scalar;
    if constexpr (IntersectionMethod<M>) {
        const auto h = M::intersect(p, r);
        if (h.has_value() != M::occluded(p, r)) {
            FAIL_CHECK("occluded() disagrees with intersect()");
        }
        return h;
    } else {
        if (M::occluded(p, r)) {
            return PrimHit<T>{std::numeric_limits<T>::quiet_NaN(), 0, 0};
        }
        return std::nullopt;
    }
}

/// A random triangle with edges of length about 1..3 around a random centre.
template <class T>
Triangle<T> random_triangle(Rng& rng) {
    const Vec3d c = rng.vec(-3, 3);
    return {Vec3<T>(c + rng.vec(-2, 2)), Vec3<T>(c + rng.vec(-2, 2)), Vec3<T>(c + rng.vec(-2, 2))};
}

/// Reference hit point of barycentrics (u, v), in double.
template <class T>
Vec3d point_at(const Triangle<T>& tri, double u, double v) {
    return Vec3d(tri.p0) * (1 - u - v) + Vec3d(tri.p1) * u + Vec3d(tri.p2) * v;
}

/// Checks a hit against the analytic (t, u, v); t only for methods that report it.
template <class M>
void check_hit(const std::optional<PrimHit<typename M::Scalar>>& h, double t, double u, double v) {
    REQUIRE(h.has_value());
    if constexpr (IntersectionMethod<M>) {
        using T = typename M::Scalar;
        CHECK(static_cast<double>(h->t) == Approx(t).epsilon(tol<T>()));
        CHECK(static_cast<double>(h->u) == Approx(u).margin(tol<T>()));
        CHECK(static_cast<double>(h->v) == Approx(v).margin(tol<T>()));
    }
}

/// True when the method's answer holds no NaN or infinity (occlusion-only t is NaN by design).
template <class M>
bool finite_hit(const std::optional<PrimHit<typename M::Scalar>>& h) {
    if (!h) {
        return true;
    }
    return (!IntersectionMethod<M> || std::isfinite(h->t)) && std::isfinite(h->u) &&
           std::isfinite(h->v);
}

/// Every triangle method in float and in double.
using AllMethods = decltype(std::tuple_cat(TriangleMethods<float>{}, TriangleMethods<double>{}));

}  // namespace

TEST_CASE("method list names every triangle method once", "[intersect][triangle]") {
    std::vector<std::string> names;
    for_each_triangle_method<float>([&]<class M>() { names.emplace_back(M::name); });
    CHECK(names ==
          std::vector<std::string>{"moller_trumbore", "badouel", "segura_feito", "watertight"});
    std::size_t intersectors = 0;
    for_each_triangle_intersector<double>([&]<class M>() {
        STATIC_REQUIRE(IntersectionMethod<M>);
        ++intersectors;
    });
    CHECK(intersectors == 3);
}

TEMPLATE_LIST_TEST_CASE("axis-aligned hit has the exact t, u, v",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const auto p = M::prepare({{0, 0, 3}, {4, 0, 3}, {0, 4, 3}});
    const Ray<T> ray{{1, 1, 0}, {0, 0, T(1.5)}};
    const auto h = probe<M>(p, ray);
    check_hit<M>(h, 2, 0.25, 0.25);
    CHECK(M::bounds(p) == Bounds3<T>{{0, 0, 3}, {4, 4, 3}});
}

TEMPLATE_LIST_TEST_CASE("random interior hits match the analytic t, u, v on both faces",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    Rng rng(7);
    for (int i = 0; i < 200; ++i) {
        const Triangle<T> tri = random_triangle<T>(rng);
        const double u = rng.uniform(0.05, 0.45), v = rng.uniform(0.05, 0.45);
        const double t = rng.uniform(0.5, 5);
        const Vec3<T> dir(rng.unit() * rng.uniform(0.5, 2));
        const Vec3d n = normalize(cross(Vec3d(tri.p1 - tri.p0), Vec3d(tri.p2 - tri.p0)));
        if (std::abs(dot(n, normalize(Vec3d(dir)))) < 0.2) {
            continue;  // keep away from grazing angles, where float t loses digits
        }
        const Ray<T> ray{Vec3<T>(point_at(tri, u, v) - Vec3d(dir) * t), dir};
        CAPTURE(i, u, v, t);
        check_hit<M>(probe<M>(M::prepare(tri), ray), t, u, v);
        // The same triangle wound the other way: still a hit, with u and v swapped.
        check_hit<M>(probe<M>(M::prepare({tri.p0, tri.p2, tri.p1}), ray), t, v, u);
    }
}

TEMPLATE_LIST_TEST_CASE("misses: behind, beside, parallel", "[intersect][triangle]", AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const auto p = M::prepare({{0, 0, 3}, {4, 0, 3}, {0, 4, 3}});
    CHECK_FALSE(probe<M>(p, Ray<T>{{1, 1, 0}, {0, 0, -1}}));           // triangle behind the origin
    CHECK_FALSE(probe<M>(p, Ray<T>{{1, 1, 5}, {0, 0, 1}}));            // past the triangle
    CHECK_FALSE(probe<M>(p, Ray<T>{{3, 3, 0}, {0, 0, 1}}));            // beyond the hypotenuse
    CHECK_FALSE(probe<M>(p, Ray<T>{{-1, 1, 0}, {0, 0, 1}}));           // left of the p0-p2 edge
    CHECK_FALSE(probe<M>(p, Ray<T>{{1, -1, 0}, {0, 0, 1}}));           // below the p0-p1 edge
    CHECK_FALSE(probe<M>(p, Ray<T>{{1, 1, 2}, {1, 0, 0}}));            // parallel, off the plane
    const auto in_plane = probe<M>(p, Ray<T>{{-1, 1, 3}, {1, 0, 0}});  // in the plane
    CHECK_FALSE(in_plane);  // documented: a ray in the triangle's plane is a miss
}

TEMPLATE_LIST_TEST_CASE("the ray window [tmin, tmax] is inclusive and honoured",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const auto p = M::prepare({{0, 0, 3}, {4, 0, 3}, {0, 4, 3}});
    const Vec3<T> org{1, 1, 0}, dir{0, 0, T(1.5)};  // exact hit at t = 2
    const T below = std::nextafter(T(2), T(0)), above = std::nextafter(T(2), T(3));
    CHECK(probe<M>(p, Ray<T>{org, dir, 0, 2}));
    CHECK(probe<M>(p, Ray<T>{org, dir, 2, 2}));
    CHECK(probe<M>(p, Ray<T>{org, dir, 2, std::numeric_limits<T>::infinity()}));
    CHECK_FALSE(probe<M>(p, Ray<T>{org, dir, 0, below}));
    CHECK_FALSE(probe<M>(p, Ray<T>{org, dir, above, 10}));
    CHECK_FALSE(probe<M>(p, Ray<T>{org, dir, 0, T(1.99)}));
    CHECK_FALSE(probe<M>(p, Ray<T>{org, dir, T(2.01), 10}));
    // An oblique ray, window around its (inexact) t.
    Rng rng(11);
    for (int i = 0; i < 100; ++i) {
        const Triangle<T> tri = random_triangle<T>(rng);
        const double t = rng.uniform(1, 4);
        const Vec3<T> d(rng.unit());
        const Vec3d n = normalize(cross(Vec3d(tri.p1 - tri.p0), Vec3d(tri.p2 - tri.p0)));
        if (std::abs(dot(n, Vec3d(d))) < 0.2) {
            continue;
        }
        const Ray<T> ray{Vec3<T>(point_at(tri, 0.3, 0.3) - Vec3d(d) * t), d};
        const auto q = M::prepare(tri);
        const T lo = static_cast<T>(t * (1 - 1e-3)), hi = static_cast<T>(t * (1 + 1e-3));
        CAPTURE(i, t);
        CHECK(probe<M>(q, Ray<T>{ray.org, ray.dir, lo, hi}));
        CHECK_FALSE(probe<M>(q, Ray<T>{ray.org, ray.dir, 0, lo}));
        CHECK_FALSE(probe<M>(q, Ray<T>{ray.org, ray.dir, hi, 100}));
    }
}

TEMPLATE_LIST_TEST_CASE("directions with zero components on one and two axes",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    Rng rng(13);
    int tested = 0;
    for (int i = 0; i < 300; ++i) {
        Vec3d d;
        const std::size_t axis = static_cast<std::size_t>(i % 3);
        d[axis] = i % 2 == 0 ? 1.0 : -1.0;
        if (i % 4 < 2) {
            d[(axis + 1 + static_cast<std::size_t>(i / 3) % 2) % 3] = rng.uniform(-1, 1);
        }
        const Vec3<T> dir(d);
        const Triangle<T> tri = random_triangle<T>(rng);
        const Vec3d n = normalize(cross(Vec3d(tri.p1 - tri.p0), Vec3d(tri.p2 - tri.p0)));
        if (std::abs(dot(n, normalize(d))) < 0.2) {
            continue;
        }
        const double u = rng.uniform(0.05, 0.45), v = rng.uniform(0.05, 0.45);
        const double t = rng.uniform(0.5, 5);
        const Ray<T> ray{Vec3<T>(point_at(tri, u, v) - Vec3d(dir) * t), dir};
        CAPTURE(i, d.x, d.y, d.z);
        check_hit<M>(probe<M>(M::prepare(tri), ray), t, u, v);
        // Moved sideways by a whole triangle size along a zero component: a miss.
        if (d[(axis + 2) % 3] == 0) {
            Ray<T> off = ray;
            off.org[(axis + 2) % 3] += T(10);
            CHECK_FALSE(probe<M>(M::prepare(tri), off));
        }
        ++tested;
    }
    CHECK(tested > 100);
}

TEMPLATE_LIST_TEST_CASE("rays through a shared edge or vertex hit at least one triangle",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    // Unit square split along its diagonal; every coordinate below is exact.
    const auto a = M::prepare({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
    const auto b = M::prepare({{0, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const Vec3<T> targets[] = {{T(0.5), T(0.5), 0}, {T(0.25), T(0.25), 0}, {1, 1, 0},
                               {0, 0, 0},           {T(0.5), 0, 0},        {0, T(0.75), 0}};
    const Vec3<T> dirs[] = {{0, 0, -1}, {T(0.25), T(-0.5), -1}, {T(-1), T(1), T(-0.5)}};
    for (const Vec3<T>& target : targets) {
        for (const Vec3<T>& d : dirs) {
            const Ray<T> ray{target - d * T(2), d};
            CAPTURE(target.x, target.y, d.x, d.y, d.z);
            const auto ha = probe<M>(a, ray), hb = probe<M>(b, ray);
            CHECK((ha || hb));
            CHECK(finite_hit<M>(ha));
            CHECK(finite_hit<M>(hb));
        }
    }
    // Grazing: a ray in the plane along the diagonal, and one a hair above it.
    const Ray<T> in_plane{{-1, -1, 0}, {1, 1, 0}};
    CHECK(finite_hit<M>(probe<M>(a, in_plane)));
    const Ray<T> above{{-1, -1, std::numeric_limits<T>::epsilon()}, {1, 1, 0}};
    CHECK_FALSE(probe<M>(a, above));
}

TEMPLATE_LIST_TEST_CASE("degenerate triangles never hit and never give NaN",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const Triangle<T> degenerate[] = {
        {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}},  // a point
        {{0, 0, 1}, {2, 2, 1}, {2, 2, 1}},  // repeated vertex
        {{0, 0, 1}, {1, 1, 1}, {2, 2, 1}},  // collinear
        {{T(0.1), T(0.2), T(0.3)}, {T(0.2), T(0.4), T(0.6)}, {T(0.4), T(0.8), T(1.2)}},
    };
    Rng rng(17);
    for (const Triangle<T>& tri : degenerate) {
        const auto p = M::prepare(tri);
        CHECK_FALSE(M::bounds(p).empty());
        for (int i = 0; i < 200; ++i) {
            // Aim at a point of the segment the triangle collapses to, from anywhere.
            const Vec3d target = point_at(tri, rng.uniform(0, 1), 0);
            const Vec3d org = rng.vec(-3, 3);
            const Ray<T> ray{Vec3<T>(org), Vec3<T>(target - org)};
            CHECK_FALSE(probe<M>(p, ray));
        }
    }
}

TEMPLATE_LIST_TEST_CASE("denormal and huge directions give no NaN",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const T tiny = std::numeric_limits<T>::denorm_min();
    const T small = std::numeric_limits<T>::min();
    const T big = std::numeric_limits<T>::max() / T(4);
    const auto p = M::prepare({{0, 0, 3}, {4, 0, 3}, {0, 4, 3}});
    const Vec3<T> dirs[] = {{0, 0, tiny},     {tiny, tiny, tiny}, {0, tiny, small},
                            {tiny, 0, small}, {0, 0, small},      {small, small, small * 64},
                            {0, 0, big},      {big, big, big},    {tiny, 0, big}};
    for (const Vec3<T>& d : dirs) {
        CAPTURE(d.x, d.y, d.z);
        const auto h = probe<M>(p, Ray<T>{{1, 1, 0}, d});
        CHECK(finite_hit<M>(h));
    }
}

TEMPLATE_LIST_TEST_CASE("methods agree with the double-precision plane solution away from edges",
                        "[intersect][triangle]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    Rng rng(19);
    int hits = 0, misses = 0;
    for (int i = 0; i < 2000; ++i) {
        const Triangle<T> tri = random_triangle<T>(rng);
        // Aim at barycentrics in [-0.3, 1.3], so about half the rays hit.
        const Vec3d org = rng.vec(-6, 6);
        const Vec3d aim = point_at(tri, rng.uniform(-0.3, 1.3), rng.uniform(-0.3, 0.7));
        const double scale = rng.uniform(-0.5, 2);  // t = 1 / scale: some behind the origin
        const Ray<T> ray{Vec3<T>(org), Vec3<T>((aim - org) * scale)};
        if (std::abs(scale) < 0.05 || length_squared(Vec3d(ray.dir)) == 0) {
            continue;
        }
        const Triangled trid{Vec3d(tri.p0), Vec3d(tri.p1), Vec3d(tri.p2)};
        const Rayd rayd(ray);
        // Reference barycentrics of the line/plane point, to know the distance from the edges.
        const Vec3d n = cross(trid.p1 - trid.p0, trid.p2 - trid.p0);
        const double cosine = dot(normalize(n), normalize(rayd.dir));
        if (std::abs(cosine) < 0.05) {
            continue;
        }
        const double t_plane = dot(n, trid.p0 - rayd.org) / dot(n, rayd.dir);
        const Vec3d x = rayd.at(t_plane) - trid.p0;
        const double u = dot(cross(x, trid.p2 - trid.p0), n) / dot(n, n);
        const double v = dot(cross(trid.p1 - trid.p0, x), n) / dot(n, n);
        const double margin = std::min({u, v, 1 - u - v});  // < 0 outside, distance-like
        const auto h = probe<M>(M::prepare(tri), ray);
        CAPTURE(i, margin, t_plane);
        if (std::abs(margin) < 1e-3 || std::abs(t_plane) < 1e-3) {
            continue;  // near an edge or the origin: the methods may legitimately differ
        }
        const bool expect = margin > 0 && t_plane > 0;
        REQUIRE(h.has_value() == expect);
        if (expect && IntersectionMethod<M>) {
            CHECK(static_cast<double>(h->t) == Approx(t_plane).epsilon(tol<T>() * 10));
        }
        (expect ? hits : misses)++;
    }
    CHECK(hits > 50);
    CHECK(misses > 50);
}

TEMPLATE_LIST_TEST_CASE("perturbed sphere mesh: rays from inside hit, every method in float",
                        "[intersect][triangle][watertight]",
                        AllMethods) {
    using M = TestType;
    using T = typename M::Scalar;
    const IndexedMesh mesh = perturbed_sphere_mesh(3, 8, 12, 0.15);
    std::vector<typename M::Prepared> prims;
    for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        prims.push_back(M::prepare(mesh.triangle<T>(i)));
    }
    bool all_finite = true;
    const auto hits_mesh = [&](const Ray<T>& ray) {
        bool hit = false;
        for (const auto& p : prims) {
            const auto h = probe<M>(p, ray);
            all_finite = all_finite && finite_hit<M>(h);
            hit = hit || h.has_value();
        }
        return hit;
    };
    Rng rng(23);
    std::size_t missed_random = 0, missed_vertex = 0, rays = 0;
    for (int i = 0; i < 500; ++i) {
        const Ray<T> ray{Vec3<T>(rng.unit() * (0.5 * rng.uniform(0, 1))), Vec3<T>(rng.unit())};
        missed_random += hits_mesh(ray) ? 0 : 1;
    }
    // Exactly at vertices from the exact centre: the rays every kernel finds hardest.
    for (const Vec3f& v : mesh.vertices) {
        for (const float scale : {0.25f, 1.0f, 8.0f}) {
            missed_vertex += hits_mesh(Ray<T>{{0, 0, 0}, Vec3<T>(v * scale)}) ? 0 : 1;
            ++rays;
        }
    }
    CAPTURE(missed_random, missed_vertex, rays);
    CHECK(all_finite);
    if constexpr (std::is_same_v<M, Watertight<T>>) {
        CHECK(missed_random == 0);  // watertight: no ray from inside a closed mesh escapes
        CHECK(missed_vertex == 0);
    } else {
        CHECK(missed_random <= 2);  // others may leak through edges and vertices, rarely
    }
}

TEMPLATE_TEST_CASE("watertight: every ray from inside a closed perturbed mesh hits",
                   "[intersect][triangle][watertight]",
                   float,
                   double) {
    using T = TestType;
    using M = Watertight<T>;
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const IndexedMesh mesh = perturbed_sphere_mesh(seed, 10, 14, 0.2);
        std::vector<typename M::Prepared> prims;
        for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
            prims.push_back(M::prepare(mesh.triangle<T>(i)));
        }
        const auto closest = [&](const Ray<T>& ray) {
            std::optional<PrimHit<T>> best;
            Ray<T> r = ray;
            const WatertightRay<T> pre = WatertightRay<T>::make(r);
            for (const auto& p : prims) {
                if (const auto h = M::intersect(p, r, pre)) {
                    best = h;
                    r.tmax = h->t;
                }
            }
            return best;
        };
        Rng rng(seed * 101);
        for (int i = 0; i < 1000; ++i) {
            // Origins inside, including on the axes and at the centre; some axis directions.
            Vec3d org = rng.unit() * (0.6 * rng.uniform(0, 1));
            Vec3d dir = rng.unit();
            if (i % 5 == 0) {
                org = Vec3d{};
            }
            if (i % 7 == 0) {
                dir = Vec3d{};
                dir[static_cast<std::size_t>(i % 3)] = i % 2 ? 1 : -1;
            }
            const Ray<T> ray{Vec3<T>(org), Vec3<T>(dir)};
            CAPTURE(seed, i);
            const auto h = closest(ray);
            REQUIRE(h.has_value());
            CHECK(h->t > T(0.3));
        }
        for (const Vec3f& v : mesh.vertices) {
            const Ray<T> ray{{0, 0, 0}, Vec3<T>(v)};
            const auto h = closest(ray);
            REQUIRE(h.has_value());
            CHECK(h->t == Approx(1).epsilon(tol<T>()));  // the vertex is at t = 1
        }
    }
}
