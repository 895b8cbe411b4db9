// Per-ray set-up (intersect/method.h): for every method of every family list, in float and
// double, the answer with the ray's data precomputed once (precompute_ray + intersect_with /
// occluded_with) is bit-identical to the plain call, on random, axis-aligned and edge-aimed rays
// with varied windows, the set-up done on the default window (RayData ignores the window). Also
// checks the lists themselves (unique names, intersectors filtered).
#include "intersect/box/methods.h"
#include "intersect/cone/methods.h"
#include "intersect/implicit/methods.h"
#include "intersect/polygon/methods.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

using namespace rtlab;

namespace {

/// Seeded uniform doubles.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : g_(seed) {}
    /// Uniform in [a, b).
    double uni(double a, double b) {
        return a + (b - a) * static_cast<double>(g_() >> 11) * 0x1.0p-53;
    }
    /// Index in [0, n).
    std::size_t below(std::size_t n) { return static_cast<std::size_t>(g_() % n); }
    /// Point in the cube [-r, r]^3.
    Vec3d point(double r) { return {uni(-r, r), uni(-r, r), uni(-r, r)}; }

private:
    std::mt19937_64 g_;
};

/// Same bits (so -0.0 != 0.0 and NaN == NaN with the same payload).
template <class T>
bool same_bits(T a, T b) {
    using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    return std::bit_cast<U>(a) == std::bit_cast<U>(b);
}

/// Rays of three kinds against targets: random, axis-aligned (zero and -0.0 components), aimed
/// at an edge point; windows vary (tmin > 0, finite tmax, [0, inf)).
std::vector<Rayd> test_rays(Rng& rng, const std::vector<Vec3d>& edge_points, std::size_t n) {
    std::vector<Rayd> rays;
    for (std::size_t i = 0; i < n; ++i) {
        Rayd r;
        r.org = rng.point(3.0);
        switch (i % 3) {
        case 0:
            r.dir = rng.point(1.0);
            break;
        case 1: {
            const std::size_t a = rng.below(3);
            r.dir = Vec3d{rng.below(2) ? 0.0 : -0.0, rng.below(2) ? 0.0 : -0.0, 0.0};
            r.dir[a] = rng.below(2) ? 1.0 : -1.0;
            r.org[(a + 1) % 3] = rng.uni(-0.5, 0.5);
            break;
        }
        default:
            r.dir = edge_points[rng.below(edge_points.size())] - r.org;
            break;
        }
        if (i % 4 == 1) {
            r.tmin = rng.uni(0.0, 0.5);
        }
        if (i % 5 == 2) {
            r.tmax = rng.uni(0.5, 2.0);
        }
        rays.push_back(r);
    }
    return rays;
}

/// Checks precomputed and plain answers agree bit for bit for method M on every shape and ray.
template <class M, class Shape>
void check_method(const std::vector<Shape>& shapes, const std::vector<Rayd>& rays_d) {
    using T = typename M::Scalar;
    CAPTURE(std::string(M::name), sizeof(T));
    std::size_t hits = 0;
    for (const Rayd& rd : rays_d) {
        const Ray<T> ray(rd);
        // Set up on the ray's default window: the data must not depend on [tmin, tmax].
        const RayDataOf<M> data = precompute_ray<M>(Ray<T>{ray.org, ray.dir});
        for (const Shape& s : shapes) {
            const typename M::Prepared p = M::prepare(s);
            const bool occ = occluded_with<M>(p, ray, data);
            REQUIRE(occ == M::occluded(p, ray));
            if constexpr (IntersectionMethod<M>) {
                const auto with = intersect_with<M>(p, ray, data);
                const auto plain = M::intersect(p, ray);
                REQUIRE(with.has_value() == plain.has_value());
                if (plain) {
                    REQUIRE(same_bits(with->t, plain->t));
                    REQUIRE(same_bits(with->u, plain->u));
                    REQUIRE(same_bits(with->v, plain->v));
                }
            }
            hits += occ ? 1 : 0;
        }
    }
    CHECK(hits > 0);  // the rays exercise the hit path too
}

/// Runs check_method for every method of the list in scalar T; shapes(T{}) gives the shapes.
template <class List, class Shapes>
void check_list(const Shapes& shapes, const std::vector<Rayd>& rays) {
    for_each_type<List>([&]<class M>() { check_method<M>(shapes(typename M::Scalar{}), rays); });
}

template <class T>
std::vector<Triangle<T>> triangles(Rng& rng, std::vector<Vec3d>& edges) {
    std::vector<Triangle<T>> out;
    for (int i = 0; i < 8; ++i) {
        const Vec3d a = rng.point(1.0), b = rng.point(1.0), c = rng.point(1.0);
        out.push_back({Vec3<T>(a), Vec3<T>(b), Vec3<T>(c)});
        edges.push_back(a);
        edges.push_back((a + b) * 0.5);
    }
    // Two triangles sharing an edge, and a zero-area one.
    out.push_back({Vec3<T>(0, 0, 0), Vec3<T>(1, 0, 0), Vec3<T>(0, 1, 0)});
    out.push_back({Vec3<T>(1, 0, 0), Vec3<T>(1, 1, 0), Vec3<T>(0, 1, 0)});
    out.push_back({Vec3<T>(0, 0, 0), Vec3<T>(1, 1, 1), Vec3<T>(2, 2, 2)});
    edges.push_back({0.5, 0.5, 0.0});
    edges.push_back({1.0, 0.0, 0.0});
    return out;
}

}  // namespace

TEST_CASE("method lists: names unique, intersectors are the t-reporting methods",
          "[intersect][setup]") {
    STATIC_REQUIRE(names_unique<TriangleMethods<double>>());
    STATIC_REQUIRE(names_unique<SphereMethods<double>>());
    STATIC_REQUIRE(names_unique<PolygonMethods<double>>());
    STATIC_REQUIRE(names_unique<AabbMethods<double>>());
    STATIC_REQUIRE(names_unique<ObbMethods<double>>());
    STATIC_REQUIRE(names_unique<ConeMethods<double>>());
    STATIC_REQUIRE(names_unique<ImplicitMethods<TangleCube, double>>());
    std::size_t all = 0, with_t = 0;
    for_each_type<TriangleMethods<float>>([&]<class M>() {
        ++all;
        with_t += IntersectionMethod<M> ? 1 : 0;
    });
    std::size_t listed = 0;
    for_each_type<TriangleIntersectors<float>>([&]<class M>() {
        STATIC_REQUIRE(IntersectionMethod<M>);
        ++listed;
    });
    CHECK(listed == with_t);
    CHECK(all > listed);  // Segura–Feito is occlusion-only
}

TEST_CASE("per-ray set-up: triangle methods bit-identical", "[intersect][setup][triangle]") {
    Rng rng(11);
    std::vector<Vec3d> edges;
    const auto f = triangles<float>(rng, edges);
    Rng rng_d(11);
    std::vector<Vec3d> unused;
    const auto d = triangles<double>(rng_d, unused);
    const std::vector<Rayd> rays = test_rays(rng, edges, 900);
    check_list<TriangleMethods<float>>([&](float) { return f; }, rays);
    check_list<TriangleMethods<double>>([&](double) { return d; }, rays);
}

TEST_CASE("per-ray set-up: sphere methods bit-identical", "[intersect][setup][sphere]") {
    Rng rng(12);
    std::vector<Sphered> spheres;
    std::vector<Vec3d> edges;
    for (int i = 0; i < 8; ++i) {
        const Sphered s{rng.point(1.0), rng.uni(0.05, 0.8)};
        spheres.push_back(s);
        edges.push_back(s.center + Vec3d{s.radius, 0.0, 0.0});
    }
    const std::vector<Rayd> rays = test_rays(rng, edges, 900);
    const auto shapes = [&](auto x) {
        using T = decltype(x);
        std::vector<Sphere<T>> out;
        for (const Sphered& s : spheres) {
            out.push_back({Vec3<T>(s.center), static_cast<T>(s.radius)});
        }
        return out;
    };
    check_list<SphereMethods<float>>(shapes, rays);
    check_list<SphereMethods<double>>(shapes, rays);
}

TEST_CASE("per-ray set-up: cone methods bit-identical", "[intersect][setup][cone]") {
    Rng rng(17);
    std::vector<Coned> cones;
    std::vector<Vec3d> edges;
    for (int i = 0; i < 8; ++i) {
        Coned c;
        c.base = rng.point(1.0);
        c.apex = c.base + rng.point(0.8);
        c.base_radius = rng.uni(0.05, 0.6);
        c.apex_radius = i % 3 == 0 ? c.base_radius : (i % 3 == 1 ? 0.0 : rng.uni(0.0, 0.6));
        c.caps = static_cast<ConeCaps>(i % 4);
        cones.push_back(c);
        edges.push_back(c.base);
        edges.push_back((c.base + c.apex) * 0.5);
    }
    const std::vector<Rayd> rays = test_rays(rng, edges, 900);
    const auto shapes = [&](auto x) {
        using T = decltype(x);
        std::vector<Cone<T>> out;
        for (const Coned& c : cones) {
            out.push_back({Vec3<T>(c.base), static_cast<T>(c.base_radius), Vec3<T>(c.apex),
                           static_cast<T>(c.apex_radius), c.caps});
        }
        return out;
    };
    check_list<ConeMethods<float>>(shapes, rays);
    check_list<ConeMethods<double>>(shapes, rays);
}

TEST_CASE("per-ray set-up: box methods bit-identical", "[intersect][setup][box]") {
    Rng rng(13);
    std::vector<Bounds3d> boxes;
    std::vector<Vec3d> edges;
    for (int i = 0; i < 8; ++i) {
        const Vec3d a = rng.point(1.0), b = rng.point(1.0);
        boxes.push_back(Bounds3d(a).extend(b));
        edges.push_back(boxes.back().lo);
        edges.push_back({boxes.back().lo.x, boxes.back().hi.y, boxes.back().center().z});
    }
    boxes.push_back({{0, 0, 0}, {1, 1, 1}});  // faces on the axis-aligned rays' planes
    const std::vector<Rayd> rays = test_rays(rng, edges, 900);
    const auto aabbs = [&](auto x) {
        using T = decltype(x);
        std::vector<Bounds3<T>> out;
        for (const Bounds3d& b : boxes) {
            out.push_back({Vec3<T>(b.lo), Vec3<T>(b.hi)});
        }
        return out;
    };
    const auto obbs = [&](auto x) {
        using T = decltype(x);
        std::vector<Obb<T>> out;
        const T c = T(0.6), s = T(0.8);  // exact rotation about z
        for (const Bounds3d& b : boxes) {
            out.push_back({Vec3<T>(b.center()),
                           {{c, s, T(0)}, {-s, c, T(0)}, {T(0), T(0), T(1)}},
                           Vec3<T>(b.diagonal() * 0.5)});
        }
        return out;
    };
    check_list<AabbMethods<float>>(aabbs, rays);
    check_list<AabbMethods<double>>(aabbs, rays);
    check_list<ObbMethods<float>>(obbs, rays);
    check_list<ObbMethods<double>>(obbs, rays);
}

TEST_CASE("per-ray set-up: polygon methods bit-identical", "[intersect][setup][polygon]") {
    Rng rng(14);
    std::vector<std::vector<Vec3d>> polys;
    std::vector<Vec3d> edges;
    for (int i = 0; i < 6; ++i) {
        // A tilted convex or concave n-gon around a random centre.
        const Vec3d c = rng.point(1.0);
        const std::size_t n = 3 + rng.below(5);
        std::vector<Vec3d> v;
        for (std::size_t k = 0; k < n; ++k) {
            const double a = 6.283185307179586 * static_cast<double>(k) / static_cast<double>(n);
            const double r = (k % 2 == 1 && n > 4) ? 0.3 : 0.7;
            v.push_back(c + Vec3d{r * std::cos(a), r * std::sin(a), 0.3 * r * std::cos(a)});
        }
        edges.push_back(v[0]);
        edges.push_back((v[0] + v[1]) * 0.5);
        polys.push_back(v);
    }
    const std::vector<Rayd> rays = test_rays(rng, edges, 900);
    const auto shapes = [&](auto x) {
        using T = decltype(x);
        std::vector<Polygon<T>> out;
        for (const auto& v : polys) {
            Polygon<T> p;
            for (const Vec3d& q : v) {
                p.vertices.push_back(Vec3<T>(q));
            }
            out.push_back(p);
        }
        return out;
    };
    check_list<PolygonMethods<float>>(shapes, rays);
    check_list<PolygonMethods<double>>(shapes, rays);
}

TEST_CASE("per-ray set-up: implicit methods bit-identical", "[intersect][setup][implicit]") {
    Rng rng(15);
    const std::vector<Vec3d> edges{{1.25, 0.0, 0.0}, {0.0, 0.75, 0.25}, {2.0, 2.0, 0.0}};
    const std::vector<Rayd> rays = test_rays(rng, edges, 240);
    const auto tori = [](auto x) {
        using T = decltype(x);
        return std::vector<Torus<T>>{{Vec3<T>(T(0), T(0), T(0)), T(1), T(0.25)}};
    };
    const auto tangles = [](auto x) {
        using T = decltype(x);
        return std::vector<TangleCube<T>>{{Vec3<T>(T(0), T(0), T(0)), T(0.5)}};
    };
    check_list<ImplicitMethods<Torus, float>>(tori, rays);
    check_list<ImplicitMethods<Torus, double>>(tori, rays);
    check_list<ImplicitMethods<TangleCube, float>>(tangles, rays);
    check_list<ImplicitMethods<TangleCube, double>>(tangles, rays);
}
