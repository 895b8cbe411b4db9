// Methods written once over their scalar (intersect/lanes.h): every lane of a lane test reports
// exactly what the scalar test reports on that lane's primitive (hit or miss, and t, u, v bit for
// bit on a hit; hit or miss for an occlusion-only method), on random triangles, degenerate ones,
// and rays aimed at vertices, edges and centres, along the axes and with short windows.
#include "base/sampler.h"
#include "intersect/lanes.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace {

using namespace rtlab;

Vec3f point(Sampler& s, double r) {
    return Vec3f(s.ball(r));
}

/// Random triangles in a ball, every fourth of them degenerate (a repeated or a collinear vertex).
std::vector<Trianglef> triangles(Sampler& s, std::size_t n) {
    std::vector<Trianglef> out;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3f c = point(s, 4.0);
        Trianglef t{c + point(s, 1.0), c + point(s, 1.0), c + point(s, 1.0)};
        if (i % 8 == 3) {
            t.p2 = t.p0;
        } else if (i % 8 == 7) {
            t.p2 = t.p0 + (t.p1 - t.p0) * 2.0f;
        }
        out.push_back(t);
    }
    return out;
}

/// Rays from random origins at each triangle's vertices, edge midpoints and centre, rays along the
/// axes through the centres, and the same rays with a window ending before the triangle.
std::vector<Rayf> rays(Sampler& s, const std::vector<Trianglef>& tris) {
    std::vector<Rayf> out;
    const auto aim = [&](const Vec3f& o, const Vec3f& target, float tmax) {
        out.push_back(Rayf{o, target - o, 0.0f, tmax});
    };
    for (const Trianglef& t : tris) {
        const Vec3f centre = (t.p0 + t.p1 + t.p2) * (1.0f / 3.0f);
        for (const Vec3f& target : {t.p0, t.p1, t.p2, (t.p0 + t.p1) * 0.5f, (t.p1 + t.p2) * 0.5f,
                                    (t.p2 + t.p0) * 0.5f, centre}) {
            const Vec3f o = point(s, 12.0);
            aim(o, target, std::numeric_limits<float>::infinity());
            aim(o, target, 0.5f);
        }
        for (int axis = 0; axis < 3; ++axis) {
            Vec3f d;
            d[static_cast<std::size_t>(axis)] = 1.0f;
            aim(centre - d * 10.0f, centre, std::numeric_limits<float>::infinity());
        }
    }
    return out;
}

/// Spheres of radii from 0.01 to 1 in a ball, and rays from outside and inside at their centres,
/// grazing them and along the axes.
std::vector<Spheref> spheres(Sampler& s, std::size_t n) {
    std::vector<Spheref> out;
    for (std::size_t i = 0; i < n; ++i) {
        out.push_back({point(s, 4.0), static_cast<float>(std::pow(10.0, s.uniform(-2.0, 0.0)))});
    }
    return out;
}

std::vector<Rayf> sphere_rays(Sampler& s, const std::vector<Spheref>& balls) {
    std::vector<Rayf> out;
    const float inf = std::numeric_limits<float>::infinity();
    for (const Spheref& b : balls) {
        const Vec3f o = point(s, 12.0);
        out.push_back(Rayf{o, b.center - o, 0.0f, inf});
        out.push_back(Rayf{o, b.center - o, -inf, inf});
        out.push_back(Rayf{b.center, Vec3f(s.unit()), 0.0f, inf});  // from inside
        const Vec3f side = normalize(cross(b.center - o, Vec3f(s.unit())));
        out.push_back(Rayf{o, b.center + side * b.radius - o, 0.0f, inf});  // grazing
        out.push_back(
            Rayf{b.center - Vec3f{10.0f, 0.0f, 0.0f}, Vec3f{1.0f, 0.0f, 0.0f}, 0.0f, 9.5f});
    }
    return out;
}

/// Every lane of M's lane test on groups of lane_count shapes against M's scalar test of that
/// lane's shape, for every ray: hit or miss and t, u, v bit for bit, or, for an occlusion-only
/// method, the occluded() answer.
template <class M, class Shape>
void check_lanes(const std::vector<Shape>& shapes, const std::vector<Rayf>& rs) {
    const auto same = [](float a, float b) {
        return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
    };
    std::size_t hits = 0;
    for (std::size_t b = 0; b + lane_count <= shapes.size(); b += lane_count) {
        typename M::Lanes g{};
        std::vector<typename M::Prepared> p;
        for (unsigned k = 0; k < lane_count; ++k) {
            p.push_back(M::prepare(shapes[b + k]));
            M::set_lane(g, k, p.back());
        }
        for (const Rayf& r : rs) {
            const MaskLanes mask = lane_occluded<M>(g, r, precompute_ray<M>(r));
            for (unsigned k = 0; k < lane_count; ++k) {
                CAPTURE(M::name, b, k, r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z,
                        r.tmax);
                if constexpr (LaneMethod<M>) {
                    const LaneHit<FloatLanes> l = lane_test<M>(g, r, precompute_ray<M>(r));
                    const auto one = M::intersect(p[k], r);
                    REQUIRE((l.hit[k] != 0) == one.has_value());
                    if (one) {
                        REQUIRE(
                            (same(l.t[k], one->t) && same(l.u[k], one->u) && same(l.v[k], one->v)));
                    }
                }
                const bool one = M::occluded(p[k], r);
                REQUIRE((mask[k] != 0) == one);
                hits += one ? 1 : 0;
            }
        }
    }
    CHECK(hits > shapes.size());  // the sets reach the hit path, not only the early outs
}

}  // namespace

TEST_CASE("a method's lane test answers as its scalar test in every lane", "[lanes][methods]") {
    Sampler s(11);
    const std::vector<Trianglef> tris = triangles(s, 64);
    const std::vector<Rayf> rs = rays(s, tris);
    std::size_t lane_methods = 0;
    for_each_triangle_method<float>([&]<class M>() {
        if constexpr (HasLanes<M>) {
            check_lanes<M>(tris, rs);
            ++lane_methods;
        }
    });
    const std::vector<Spheref> balls = spheres(s, 64);
    const std::vector<Rayf> brs = sphere_rays(s, balls);
    for_each_sphere_method<float>([&]<class M>() {
        if constexpr (HasLanes<M>) {
            check_lanes<M>(balls, brs);
            ++lane_methods;
        }
    });
    CHECK(lane_methods >= 4);  // Badouel, Segura–Feito, the geometric and algebraic sphere tests
}
