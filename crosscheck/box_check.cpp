// Cross-check of the AABB and OBB methods against exact oracles. Shapes and rays are generated in
// float, so the float and double runs trace the same rays; the oracle judges the ray through the
// two points org and org + dir (summed exactly), once per ray, in parallel.
// AABB oracle: CGAL Iso_cuboid_3 with exact do_intersect / intersection against the ray or
// segment of the window [tmin, tmax]; reference t = the entry parameter max(tmin, t_enter).
// OBB oracle: the six exact half-spaces |dot(p - c, a_i)| <= h_i with the float axes taken
// exactly (the very parallelepiped the method describes), the ray clipped with GMP rationals.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/exact_ray.h"
#include "crosscheck/ray_sets.h"
#include "intersect/box/methods.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/intersections.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rtlab::xcheck {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;

/// The ray sets, in table order; each gets an equal share of opt.rays.
constexpr std::array<const char*, 6> set_names{"random", "edges", "grazing",
                                               "axis1",  "axis2", "inside"};
enum RaySet : std::uint8_t { random_set, edges_set, grazing_set, axis1_set, axis2_set, inside_set };

/// A point of the box [lo, hi] grown by `grow` of its size on each side.
Vec3f point_in(Rng& rng, const Vec3f& lo, const Vec3f& hi, float grow) {
    Vec3f p;
    for (std::size_t k = 0; k < 3; ++k) {
        const float g = (hi[k] - lo[k]) * grow;
        p[k] = rng.uni(lo[k] - g, hi[k] + g);
    }
    return p;
}

/// A ray of set `set` for the axis-aligned box [lo, hi] (box-local coordinates for OBBs).
Rayf local_ray(Rng& rng, RaySet set, const Vec3f& lo, const Vec3f& hi) {
    Rayf r;
    const float dist = rng.uni(0.5f, 4.0f);
    Vec3f target = point_in(rng, lo, hi, 0.25f);
    Vec3f dir = rng.dir();
    switch (set) {
    case random_set:
        if (rng.coin(0.25f)) {  // a finite window somewhere along the ray
            r.tmin = rng.uni(0.0f, 1.2f * dist);
            r.tmax = r.tmin + rng.uni(0.01f, 2.0f * dist);
        }
        break;
    case edges_set: {
        // A point on an edge (two coordinates on faces) or a corner (all three).
        const std::size_t free_axis = rng.below(4);
        for (std::size_t k = 0; k < 3; ++k) {
            if (k != free_axis) {
                target[k] = rng.coin(0.5f) ? lo[k] : hi[k];
            } else {
                target[k] = rng.uni(lo[k], hi[k]);
            }
        }
        break;
    }
    case grazing_set: {
        // Nearly parallel to a face, at or within 1e-6 of its plane.
        const std::size_t a = rng.below(3);
        const float plane = rng.coin(0.5f) ? lo[a] : hi[a];
        target[a] = plane;
        dir[a] = rng.coin(0.25f) ? 0.0f : rng.uni(-1e-6f, 1e-6f);
        if (length_squared(dir) < 1e-4f) {
            dir[(a + 1) % 3] = 1.0f;
        }
        r.org = target - dir * dist;
        r.org[a] = plane + tiny(rng);
        r.dir = dir;
        return r;
    }
    case axis1_set: {
        const std::size_t a = rng.below(3);
        dir[a] = zero_like(rng);
        if (length_squared(dir) < 1e-4f) {
            dir[(a + 1) % 3] = 1.0f;
        }
        r.org = target - dir * dist;
        r.org[a] = rng.coin(0.33f) ? (rng.coin(0.5f) ? lo[a] : hi[a]) : target[a];
        r.dir = dir;
        return r;
    }
    case axis2_set: {
        const std::size_t a = rng.below(3);
        dir = Vec3f{zero_like(rng), zero_like(rng), zero_like(rng)};
        dir[a] = rng.coin(0.5f) ? rng.uni(0.5f, 2.0f) : -rng.uni(0.5f, 2.0f);
        r.org = target - dir * dist;
        for (std::size_t k = 0; k < 3; ++k) {
            if (k != a && rng.coin(0.33f)) {
                r.org[k] = rng.coin(0.5f) ? lo[k] : hi[k];  // on a face plane or an edge line
            }
        }
        r.dir = dir;
        return r;
    }
    case inside_set:
        r.org = point_in(rng, lo, hi, 0.0f);
        r.dir = dir;
        return r;
    }
    r.org = target - dir * dist;
    r.dir = dir;
    return r;
}

/// Parameter of a point q on the line p1 + t (p2 - p1), along the direction's dominant axis.
double line_param(const ExactRay& er, const Vec3f& dir, const K::Point_3& q) {
    const std::size_t k = max_abs_axis(dir);
    const int ki = static_cast<int>(k);
    // exact() first: to_double of a lazy number may round its interval, not the exact value.
    return CGAL::to_double(CGAL::exact((q[ki] - er.p1[ki]) / (er.p2[ki] - er.p1[ki])));
}

/// Exact answer for an AABB: Iso_cuboid_3 against the ray (tmax infinite) or segment (finite).
Truth aabb_truth(const Bounds3f& b, const Rayf& r) {
    const ExactRay er(r);
    const K::Iso_cuboid_3 box(K::Point_3(static_cast<double>(b.lo.x), static_cast<double>(b.lo.y),
                                         static_cast<double>(b.lo.z)),
                              K::Point_3(static_cast<double>(b.hi.x), static_cast<double>(b.hi.y),
                                         static_cast<double>(b.hi.z)));
    const K::Vector_3 d = er.p2 - er.p1;
    const K::Point_3 start = r.tmin == 0.0f ? er.p1 : er.p1 + d * FT(static_cast<double>(r.tmin));
    std::optional<double> entry;
    const auto entry_of = [&](const auto& res) {
        if (!res) {
            return;
        }
        if (const K::Point_3* p = boost::get<K::Point_3>(&*res)) {
            entry = line_param(er, r.dir, *p);
        } else if (const K::Segment_3* s = boost::get<K::Segment_3>(&*res)) {
            entry =
                std::min(line_param(er, r.dir, s->source()), line_param(er, r.dir, s->target()));
        }
    };
    if (std::isinf(r.tmax)) {
        const K::Ray_3 ray(start, d);
        if (!CGAL::do_intersect(ray, box)) {
            return {};
        }
        entry_of(CGAL::intersection(ray, box));
    } else {
        const K::Segment_3 seg(start, er.p1 + d * FT(static_cast<double>(r.tmax)));
        if (!CGAL::do_intersect(seg, box)) {
            return {};
        }
        entry_of(CGAL::intersection(seg, box));
    }
    if (!entry) {
        return {};
    }
    return {true, std::max(*entry, static_cast<double>(r.tmin))};
}

/// Exact answer for an OBB: the window clipped by the three exact slabs |dot(p - c, a_i)| <= h_i,
/// in GMP rationals (several times faster here than the lazy kernel, whose every comparison of
/// two quotients near a face falls back to exact evaluation). The ray is P1 + t (P2 - P1) with
/// P2 - P1 = dir exactly, as in ExactRay.
Truth obb_truth(const Obb<float>& b, const Rayf& r) {
    using Q = CGAL::Gmpq;
    std::array<Q, 3> m, d;
    for (std::size_t k = 0; k < 3; ++k) {
        m[k] = Q(static_cast<double>(r.org[k])) - Q(static_cast<double>(b.center[k]));
        d[k] = Q(static_cast<double>(r.dir[k]));
    }
    Q lo(static_cast<double>(r.tmin));
    Q hi(0);
    bool hi_inf = std::isinf(r.tmax);
    if (!hi_inf) {
        hi = Q(static_cast<double>(r.tmax));
    }
    for (std::size_t i = 0; i < 3; ++i) {
        Q e(0), f(0);
        for (std::size_t k = 0; k < 3; ++k) {
            const Q a(static_cast<double>(b.axis[i][k]));
            e += m[k] * a;
            f += d[k] * a;
        }
        const Q h(static_cast<double>(b.half[i]));
        if (CGAL::is_zero(f)) {
            if (e < -h || e > h) {
                return {};
            }
            continue;
        }
        Q t1 = (-h - e) / f;
        Q t2 = (h - e) / f;
        if (t1 > t2) {
            std::swap(t1, t2);
        }
        if (t1 > lo) {
            lo = t1;
        }
        if (hi_inf || t2 < hi) {
            hi = t2;
            hi_inf = false;
        }
        if (lo > hi) {
            return {};
        }
    }
    return {true, CGAL::to_double(lo)};
}

/// Random AABBs in [-1, 2]^3 with sides in [0.05, 1]; one in eight is flat on one axis.
std::vector<Bounds3f> make_aabbs(Rng& rng, std::size_t n) {
    std::vector<Bounds3f> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        Vec3f lo{rng.uni(-1, 1), rng.uni(-1, 1), rng.uni(-1, 1)};
        Vec3f size{rng.uni(0.05f, 1), rng.uni(0.05f, 1), rng.uni(0.05f, 1)};
        if (rng.coin(0.125f)) {
            size[rng.below(3)] = 0.0f;
        }
        boxes.emplace_back(lo, lo + size);
    }
    return boxes;
}

/// Random OBBs: half of them freely rotated (unit quaternion), a quarter rotated about one world
/// axis (that axis exact), a quarter with signed-permutation axes (exactly axis-aligned).
std::vector<Obb<float>> make_obbs(Rng& rng, std::size_t n) {
    std::vector<Obb<float>> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        Obb<float> b;
        b.center = {rng.uni(-1, 1), rng.uni(-1, 1), rng.uni(-1, 1)};
        b.half = {rng.uni(0.03f, 0.6f), rng.uni(0.03f, 0.6f), rng.uni(0.03f, 0.6f)};
        if (rng.coin(0.125f)) {
            b.half[rng.below(3)] = 0.0f;
        }
        const std::uint32_t kind = rng.below(4);
        if (kind < 2) {
            Vec3f q3 = rng.dir();
            float w = rng.uni(-1, 1);
            const float l = std::sqrt(length_squared(q3) + w * w);
            q3 = q3 / l;
            w /= l;
            const float x = q3.x, y = q3.y, z = q3.z;
            b.axis[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
            b.axis[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
            b.axis[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
        } else if (kind == 2) {
            const std::size_t k = rng.below(3);
            const float ang = rng.uni(0, 6.2831853f);
            const float c = std::cos(ang), s = std::sin(ang);
            const std::size_t u = (k + 1) % 3, v = (k + 2) % 3;
            b.axis[0] = b.axis[1] = b.axis[2] = Vec3f{};
            b.axis[0][k] = 1.0f;
            b.axis[1][u] = c;
            b.axis[1][v] = s;
            b.axis[2][u] = -s;
            b.axis[2][v] = c;
        } else {
            std::array<std::size_t, 3> perm{0, 1, 2};
            std::swap(perm[0], perm[rng.below(3)]);
            std::swap(perm[1], perm[1 + rng.below(2)]);
            for (std::size_t a = 0; a < 3; ++a) {
                b.axis[a] = Vec3f{};
                b.axis[a][perm[a]] = rng.coin(0.5f) ? 1.0f : -1.0f;
            }
        }
        boxes.push_back(b);
    }
    return boxes;
}

/// Visits the AABB or OBB methods of precision T (see run_wanted).
constexpr auto for_each_aabb = [](auto tag, const auto& f) {
    for_each_aabb_method<typename decltype(tag)::type>(f);
};
constexpr auto for_each_obb = [](auto tag, const auto& f) {
    for_each_obb_method<typename decltype(tag)::type>(f);
};

/// The float shape in precision T, for the driver.
constexpr auto convert = []<class T>(const auto& shape, std::type_identity<T>) {
    return to_scalar<T>(shape);
};

constexpr std::size_t shape_count = 64;

/// Sample shapes for make_samples: uniform over the shape_count shapes.
auto random_shape(Rng& rng) {
    return [&rng](std::size_t, std::size_t) { return rng.below(shape_count); };
}

}  // namespace

std::vector<std::string> aabb_methods() {
    return method_names(for_each_aabb);
}

std::vector<Row> check_aabbs(const Options& opt) {
    select_methods(aabb_methods(), opt.methods, "aabb");  // reject bad names before the oracle
    Rng rng(opt.seed);
    Workload<Bounds3f> w;
    w.shapes = make_aabbs(rng, shape_count);
    w.samples = make_samples(split_rays<set_names.size()>(opt.rays), random_shape(rng),
                             [&](std::size_t s, std::uint32_t shape) {
                                 const Bounds3f& b = w.shapes[shape];
                                 return local_ray(rng, static_cast<RaySet>(s), b.lo, b.hi);
                             });
    compute_truth(w, aabb_truth);
    return run_workload("aabb", set_names, for_each_aabb, w, convert, opt);
}

std::vector<std::string> obb_methods() {
    return method_names(for_each_obb);
}

namespace {

/// A vector in the box's frame (axes b.axis) in world coordinates.
Vec3f world(const Obb<float>& b, const Vec3f& p) {
    return b.axis[0] * p.x + b.axis[1] * p.y + b.axis[2] * p.z;
}

/// local_ray in the box's own frame (centred, axes b.axis), mapped to world coordinates.
Rayf world_ray(Rng& rng, RaySet set, const Obb<float>& b) {
    const Rayf local = local_ray(rng, set, -b.half, b.half);
    Rayf ray = local;
    ray.org = b.center + world(b, local.org);
    ray.dir = world(b, local.dir);
    return ray;
}

}  // namespace

std::vector<Row> check_obbs(const Options& opt) {
    select_methods(obb_methods(), opt.methods, "obb");
    Rng rng(opt.seed);
    Workload<Obb<float>> w;
    w.shapes = make_obbs(rng, shape_count);
    w.samples = make_samples(
        split_rays<set_names.size()>(opt.rays), random_shape(rng),
        [&](std::size_t s, std::uint32_t shape) {
            const Obb<float>& b = w.shapes[shape];
            Rayf ray;
            const auto set = static_cast<RaySet>(s);
            if (set == axis1_set || set == axis2_set) {
                // Zero components in world coordinates: parallel to a slab when the box has an
                // exact world axis (three quarters of the boxes have at least one).
                const Vec3f target = b.center + world(b, point_in(rng, -b.half, b.half, 0.25f));
                Vec3f dir = rng.dir();
                const std::size_t a = rng.below(3);
                if (set == axis1_set) {
                    dir[a] = zero_like(rng);
                } else {
                    const float keep =
                        dir[a] < 0 ? -std::max(-dir[a], 0.3f) : std::max(dir[a], 0.3f);
                    dir = Vec3f{zero_like(rng), zero_like(rng), zero_like(rng)};
                    dir[a] = keep;
                }
                if (length_squared(dir) < 1e-4f) {
                    dir[(a + 1) % 3] = 1.0f;
                }
                ray.org = target - dir * rng.uni(0.5f, 4.0f);
                ray.dir = dir;
            } else {
                ray = world_ray(rng, set, b);
            }
            return ray;
        });
    compute_truth(w, obb_truth);
    return run_workload("obb", set_names, for_each_obb, w, convert, opt);
}

namespace {

/// The box-local sets behind the bench distributions (far is a pushed-back random ray).
constexpr std::array<RaySet, 4> bench_from{random_set, edges_set, grazing_set, random_set};

/// Bench cases of a box kind: n samples per bench set, each on a random one of shapes, its ray
/// ray_of(rng, box-local set, shape) (pushed far for the far set), judged by oracle.
template <class Shape, class RayOf, class Oracle>
BenchCases<Shape> box_bench_cases(
    Rng& rng, std::vector<Shape> shapes, std::size_t n, const RayOf& ray_of, Oracle oracle) {
    BenchCases<Shape> out;
    out.shapes = std::move(shapes);
    for (std::size_t s = 0; s < bench_from.size(); ++s) {
        for (std::size_t j = 0; j < n; ++j) {
            Sample smp;
            smp.shape = rng.below(shape_count);
            smp.set = static_cast<std::uint8_t>(s);
            smp.ray = ray_of(rng, bench_from[s], out.shapes[smp.shape]);
            if (s == bench_far) {
                smp.ray = push_far(rng, smp.ray);
            }
            out.samples.push_back(smp);
        }
    }
    Workload<Shape> w{out.shapes, out.samples, {}};
    compute_truth(w, oracle);
    out.truth = std::move(w.truth);
    return out;
}

}  // namespace

BenchCases<Bounds3f> aabb_bench_cases(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Bounds3f> boxes = make_aabbs(rng, shape_count);
    return box_bench_cases(
        rng, std::move(boxes), n,
        [](Rng& r, RaySet set, const Bounds3f& b) { return local_ray(r, set, b.lo, b.hi); },
        aabb_truth);
}

BenchCases<Obb<float>> obb_bench_cases(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Obb<float>> boxes = make_obbs(rng, shape_count);
    return box_bench_cases(rng, std::move(boxes), n, world_ray, obb_truth);
}

}  // namespace rtlab::xcheck
