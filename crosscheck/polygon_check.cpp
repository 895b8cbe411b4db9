// Cross-check of the polygon methods against an exact oracle. Shapes and rays are generated in
// float, so the float and double runs trace the same rays; the oracle judges the ray through the
// two points org and org + dir (summed exactly), once per ray, in parallel.
// Float vertices are not exactly coplanar, so the exact reference is defined as the methods define
// the polygon: the plane through the first vertex v0 with the exact Newell normal
// N = sum_i (v_i - v0) x (v_{i+1} - v0) of the float vertices; a ray with dot(N, d) = 0 misses
// (even one lying in the plane); otherwise the exact hit point q on that plane, with t in
// [tmin, tmax], is inside when CGAL Polygon_2::bounded_side of the exact 2D projection (dropping
// the dominant axis of N, ties to the lowest index) says bounded or boundary.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/exact_ray.h"
#include "crosscheck/ray_sets.h"
#include "intersect/polygon/methods.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vector>

namespace rtlab::xcheck {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;

/// The ray sets, in table order; each gets an equal share of opt.rays.
constexpr std::array<const char*, 6> set_names{"random", "edges", "grazing",
                                               "axis1",  "axis2", "on_plane"};
enum RaySet : std::uint8_t {
    random_set,
    edges_set,
    grazing_set,
    axis1_set,
    axis2_set,
    on_plane_set
};

/// A float polygon with the frame it was built in (for aiming rays at its plane).
struct TestPolygon {
    Polygon<float> poly;
    Vec3f center, e1, e2, normal;  ///< plane frame; normal = e1 x e2 (unit up to rounding)
    float radius = 1;              ///< the 2D shape lies within this distance of the centre
    /// The point centre + x e1 + y e2 (rounded to float, so not exactly on the plane).
    Vec3f at(float x, float y) const { return center + e1 * x + e2 * y; }
};

/// 2D outline of one of three kinds: convex (points on an ellipse), star (alternating radii,
/// concave), comb (teeth, concave); 3 to 16 vertices, counter-clockwise, within radius 1.
std::vector<std::array<float, 2>> outline(Rng& rng) {
    std::vector<std::array<float, 2>> pts;
    const std::uint32_t kind = rng.below(3);
    if (kind == 0) {
        const std::uint32_t n = 3 + rng.below(14);
        const float a = rng.uni(0.3f, 1.0f), b = rng.uni(0.3f, 1.0f);
        for (std::uint32_t i = 0; i < n; ++i) {
            const float ang =
                6.2831853f * (static_cast<float>(i) + rng.uni(0.0f, 0.8f)) / static_cast<float>(n);
            pts.push_back({a * std::cos(ang), b * std::sin(ang)});
        }
    } else if (kind == 1) {
        const std::uint32_t n = 2 * (3 + rng.below(6));  // 6 to 16
        const float r_out = rng.uni(0.6f, 1.0f), r_in = rng.uni(0.15f, 0.45f);
        for (std::uint32_t i = 0; i < n; ++i) {
            const float ang =
                6.2831853f * (static_cast<float>(i) + rng.uni(-0.3f, 0.3f)) / static_cast<float>(n);
            const float r = i % 2 == 0 ? r_out : r_in;
            pts.push_back({r * std::cos(ang), r * std::sin(ang)});
        }
    } else {
        const std::uint32_t teeth = 2 + rng.below(3);  // 8, 12 or 16 vertices
        const float w = 1.4f / static_cast<float>(2 * teeth - 1), top = 0.6f;
        const float base = rng.uni(-0.6f, 0.2f);
        const float right = -0.7f + w * static_cast<float>(2 * teeth - 1);
        pts.push_back({-0.7f, -0.6f});
        pts.push_back({right, -0.6f});
        for (std::uint32_t j = teeth; j-- > 0;) {
            const float x0 = -0.7f + w * static_cast<float>(2 * j);
            pts.push_back({x0 + w, top});
            pts.push_back({x0, top});
            if (j > 0) {
                pts.push_back({x0, base});
                pts.push_back({x0 - w, base});
            }
        }
    }
    return pts;
}

/// Random polygons: random planes (one in eight exactly axis-aligned), sizes 0.3 to 1.5, either
/// orientation.
std::vector<TestPolygon> make_polygons(Rng& rng, std::size_t count) {
    std::vector<TestPolygon> out;
    for (std::size_t i = 0; i < count; ++i) {
        TestPolygon tp;
        tp.center = {rng.uni(-2, 2), rng.uni(-2, 2), rng.uni(-2, 2)};
        if (rng.coin(0.125f)) {
            const std::size_t k = rng.below(3);
            tp.e1 = tp.e2 = Vec3f{};
            tp.e1[(k + 1) % 3] = 1.0f;
            tp.e2[(k + 2) % 3] = 1.0f;
        } else {
            const Vec3f n = normalize(rng.dir());
            const Vec3f helper = std::abs(n.x) < 0.6f ? Vec3f{1, 0, 0} : Vec3f{0, 1, 0};
            tp.e1 = normalize(cross(n, helper));
            tp.e2 = cross(n, tp.e1);
        }
        tp.normal = cross(tp.e1, tp.e2);
        tp.radius = rng.uni(0.3f, 1.5f);
        std::vector<std::array<float, 2>> pts = outline(rng);
        if (rng.coin(0.5f)) {
            std::reverse(pts.begin(), pts.end());
        }
        for (const auto& p : pts) {
            tp.poly.vertices.push_back(tp.at(p[0] * tp.radius, p[1] * tp.radius));
        }
        out.push_back(std::move(tp));
    }
    return out;
}

/// A ray of set `set` for the polygon.
Rayf polygon_ray(Rng& rng, RaySet set, const TestPolygon& tp) {
    Rayf r;
    const float dist = rng.uni(0.5f, 4.0f);
    const float g = 1.25f * tp.radius;
    Vec3f target = tp.at(rng.uni(-g, g), rng.uni(-g, g));
    Vec3f dir = rng.dir();
    switch (set) {
    case random_set:
        if (rng.coin(0.25f)) {  // a finite window somewhere along the ray
            r.tmin = rng.uni(0.0f, 1.2f * dist);
            r.tmax = r.tmin + rng.uni(0.01f, 2.0f * dist);
        }
        break;
    case edges_set: {
        const std::vector<Vec3f>& v = tp.poly.vertices;
        const std::size_t i = rng.below(static_cast<std::uint32_t>(v.size()));
        const Vec3f& a = v[i];
        const Vec3f& b = v[(i + 1) % v.size()];
        target = rng.coin(0.25f) ? a : a + (b - a) * rng.uni(0.0f, 1.0f);
        break;
    }
    case grazing_set: {
        // Nearly parallel to the plane: slope 1e-7 to 1e-3.
        const float ang = rng.uni(0, 6.2831853f);
        const float slope = std::pow(10.0f, rng.uni(-7.0f, -3.0f)) * (rng.coin(0.5f) ? 1 : -1);
        dir = tp.e1 * std::cos(ang) + tp.e2 * std::sin(ang) + tp.normal * slope;
        break;
    }
    case axis1_set:
        dir[rng.below(3)] = zero_like(rng);
        if (length_squared(dir) < 1e-4f) {
            dir = tp.normal;
        }
        break;
    case axis2_set: {
        // Along a world axis: the normal's dominant one half of the time.
        const std::size_t a = rng.coin(0.5f) ? max_abs_axis(tp.normal) : rng.below(3);
        dir = Vec3f{zero_like(rng), zero_like(rng), zero_like(rng)};
        dir[a] = rng.coin(0.5f) ? rng.uni(0.5f, 2.0f) : -rng.uni(0.5f, 2.0f);
        break;
    }
    case on_plane_set:
        // Origin on (or within 1e-6 of) the plane near the polygon; t is near 0.
        r.org = target + tp.normal * tiny(rng);
        r.dir = dir;
        return r;
    }
    r.org = target - dir * dist;
    r.dir = dir;
    return r;
}

/// The exact polygon of the reference definition (see the top of the file).
struct ExactPolygon {
    K::Point_3 v0;
    K::Vector_3 normal;
    int u = 0, v = 1;
    CGAL::Polygon_2<K> projected;

    explicit ExactPolygon(const Polygon<float>& poly) {
        std::vector<K::Point_3> p;
        for (const Vec3f& x : poly.vertices) {
            p.emplace_back(static_cast<double>(x.x), static_cast<double>(x.y),
                           static_cast<double>(x.z));
        }
        v0 = p[0];
        normal = K::Vector_3(0, 0, 0);
        for (std::size_t i = 1; i + 1 < p.size(); ++i) {
            normal = normal + CGAL::cross_product(p[i] - v0, p[i + 1] - v0);
        }
        const FT ax = CGAL::abs(normal.x()), ay = CGAL::abs(normal.y()), az = CGAL::abs(normal.z());
        const int drop = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
        u = (drop + 1) % 3;
        v = (drop + 2) % 3;
        for (const K::Point_3& q : p) {
            projected.push_back(K::Point_2(q[u], q[v]));
        }
    }

    /// Exact answer for one ray.
    Truth judge(const Rayf& r) const {
        const ExactRay er(r);
        const K::Vector_3 d = er.p2 - er.p1;
        const FT denom = normal * d;
        if (CGAL::is_zero(denom)) {
            return {};
        }
        const FT t = (normal * (v0 - er.p1)) / denom;
        if (t < FT(static_cast<double>(r.tmin)) ||
            (!std::isinf(r.tmax) && t > FT(static_cast<double>(r.tmax)))) {
            return {};
        }
        const K::Point_3 q = er.p1 + d * t;
        if (projected.bounded_side(K::Point_2(q[u], q[v])) == CGAL::ON_UNBOUNDED_SIDE) {
            return {};
        }
        // exact() first: to_double of a lazy number may round its interval, not the exact value.
        return {true, CGAL::to_double(CGAL::exact(t))};
    }
};

/// Visits the polygon methods of precision T (see run_wanted).
constexpr auto for_each_polygon = [](auto tag, const auto& f) {
    for_each_polygon_method<typename decltype(tag)::type>(f);
};

/// The float polygon in precision T, for the driver.
constexpr auto convert = []<class T>(const Polygon<float>& p, std::type_identity<T>) {
    return to_scalar<T>(p);
};

constexpr std::size_t shape_count = 64;

}  // namespace

std::vector<std::string> polygon_methods() {
    return method_names(for_each_polygon);
}

std::vector<Row> check_polygons(const Options& opt) {
    select_methods(polygon_methods(), opt.methods, "polygon");  // bad names before the oracle
    Rng rng(opt.seed);
    const std::vector<TestPolygon> tests = make_polygons(rng, shape_count);
    Workload<Polygon<float>> w;
    for (const TestPolygon& tp : tests) {
        w.shapes.push_back(tp.poly);
    }
    // Shapes in contiguous blocks per set, so the oracle reuses one exact polygon per block.
    const auto counts = split_rays<set_names.size()>(opt.rays);
    w.samples = make_samples(
        counts,
        [&](std::size_t s, std::size_t j) {
            return static_cast<std::uint32_t>(j * shape_count / counts[s]);
        },
        [&](std::size_t s, std::uint32_t shape) {
            return polygon_ray(rng, static_cast<RaySet>(s), tests[shape]);
        });
    w.truth.assign(w.samples.size(), Truth{});
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, w.samples.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          std::optional<ExactPolygon> exact;
                          std::uint32_t cached = 0;
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              const Sample& s = w.samples[i];
                              if (!exact || cached != s.shape) {
                                  exact.emplace(w.shapes[s.shape]);
                                  cached = s.shape;
                              }
                              w.truth[i] = exact->judge(s.ray);
                          }
                      });
    return run_workload("polygon", set_names, for_each_polygon, w, convert, opt);
}

BenchCases<Polygon<float>> polygon_bench_cases(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    const std::vector<TestPolygon> tests = make_polygons(rng, shape_count);
    BenchCases<Polygon<float>> out;
    for (const TestPolygon& tp : tests) {
        out.shapes.push_back(tp.poly);
    }
    const std::array<RaySet, 4> from{random_set, edges_set, grazing_set, random_set};
    for (std::size_t s = 0; s < from.size(); ++s) {
        for (std::size_t j = 0; j < n; ++j) {
            Sample smp;
            smp.shape = static_cast<std::uint32_t>(j * shape_count / n);
            smp.set = static_cast<std::uint8_t>(s);
            smp.ray = polygon_ray(rng, from[s], tests[smp.shape]);
            if (s == bench_far) {
                smp.ray = push_far(rng, smp.ray);
            }
            out.samples.push_back(smp);
        }
    }
    out.truth.assign(out.samples.size(), Truth{});
    tbb::parallel_for(std::size_t(0), out.samples.size(), [&](std::size_t i) {
        const Sample& smp = out.samples[i];
        out.truth[i] = ExactPolygon(out.shapes[smp.shape]).judge(smp.ray);
    });
    return out;
}

}  // namespace rtlab::xcheck
