// Grazing rays: rays nearly tangent to spheres, nearly parallel to triangles' planes and nearly
// parallel to box faces, judged by exact rational arithmetic (CGAL::Gmpq) on the very float ray and
// shape traced; false hits, false misses and relative t error per method and precision, with ns per
// test. Nearness is log-uniform: a relative offset or angle in [1e-8, 1e-1] of either sign, plus
// exact zeros for boxes; half the box rays pass near an edge.
#include "intersect/box/methods.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"
#include "stability/case_util.h"
#include "stability/cases.h"

#include <CGAL/Gmpq.h>

#include <cmath>
#include <optional>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <type_traits>

namespace rtlab::stab {

namespace {

using Q = CGAL::Gmpq;

/// The exact answer for one ray: hit or not, and the nearest t in the window (rounded).
struct Truth {
    bool hit = false;
    double t = 0;
};

/// One shape (in float) with its ray and exact answer.
template <class Shape>
struct Sample {
    Shape shape;
    Rayf ray;
    Truth truth;
};

/// A float exactly, as a rational.
Q q(float x) {
    return Q(static_cast<double>(x));
}

struct QVec {
    Q x, y, z;
};
QVec qv(const Vec3f& v) {
    return {q(v.x), q(v.y), q(v.z)};
}
QVec sub(const QVec& a, const QVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Q qdot(const QVec& a, const QVec& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
QVec qcross(const QVec& a, const QVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Exact sphere answer for the window [0, inf) (rays start outside): roots of
/// a t^2 + 2 b t + c = 0 with a = d.d, b = f.d, c = f.f - r^2, f = o - centre.
Truth sphere_truth(const Sphere<float>& s, const Rayf& r) {
    const QVec f = sub(qv(r.org), qv(s.center));
    const QVec d = qv(r.dir);
    const Q a = qdot(d, d);
    const Q b = qdot(f, d);
    const Q c = qdot(f, f) - q(s.radius) * q(s.radius);
    const Q disc = b * b - a * c;
    if (disc < 0 || (c > 0 && b >= 0)) {
        return {};
    }
    const double sq = std::sqrt(CGAL::to_double(disc));
    if (c > 0) {
        // Near root in the stable form c / (-b + sqrt(disc)): no cancellation since -b > 0.
        return {true, CGAL::to_double(c) / (-CGAL::to_double(b) + sq)};
    }
    return {true, (-CGAL::to_double(b) + sq) / CGAL::to_double(a)};
}

/// Exact triangle answer for the window [0, inf): the plane hit point inside the closed
/// triangle. A ray parallel to the plane counts as a miss (the generator never puts one in it).
Truth triangle_truth(const Triangle<float>& tri, const Rayf& r) {
    const QVec p0 = qv(tri.p0), p1 = qv(tri.p1), p2 = qv(tri.p2);
    const QVec o = qv(r.org), d = qv(r.dir);
    const QVec n = qcross(sub(p1, p0), sub(p2, p0));
    const Q den = qdot(n, d);
    if (den == 0) {
        return {};
    }
    const Q t = qdot(n, sub(p0, o)) / den;
    if (t < 0) {
        return {};
    }
    const QVec x{o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
    const Q s0 = qdot(qcross(sub(p1, p0), sub(x, p0)), n);
    const Q s1 = qdot(qcross(sub(p2, p1), sub(x, p1)), n);
    const Q s2 = qdot(qcross(sub(p0, p2), sub(x, p2)), n);
    if (s0 < 0 || s1 < 0 || s2 < 0) {
        return {};
    }
    return {true, CGAL::to_double(t)};
}

/// Exact box answer for the window [0, inf): the entry parameter (0 when inside).
Truth box_truth(const Bounds3f& b, const Rayf& r) {
    Q t0 = 0;
    std::optional<Q> t1;
    for (std::size_t k = 0; k < 3; ++k) {
        const Q o = q(r.org[k]), lo = q(b.lo[k]), hi = q(b.hi[k]);
        if (r.dir[k] == 0.0f) {
            if (o < lo || o > hi) {
                return {};
            }
            continue;
        }
        const Q d = q(r.dir[k]);
        Q ta = (lo - o) / d, tb = (hi - o) / d;
        if (tb < ta) {
            std::swap(ta, tb);
        }
        if (ta > t0) {
            t0 = ta;
        }
        if (!t1 || tb < *t1) {
            t1 = tb;
        }
    }
    if (t1 && t0 > *t1) {
        return {};
    }
    return {true, CGAL::to_double(t0)};
}

/// Log-uniform magnitude in [1e-8, 1e-1] with a random sign.
double near_zero(Sampler& rng) {
    return (rng.index(2) ? 1.0 : -1.0) * std::pow(10.0, rng.uniform(-8, -1));
}

std::vector<Sample<Sphere<float>>> sphere_samples(std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 601);
    std::vector<Sample<Sphere<float>>> out(n);
    for (auto& s : out) {
        const Vec3d c{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
        const double r = 0.1 * std::pow(50.0, rng.uniform(0, 1));
        s.shape = {Vec3f(c), static_cast<float>(r)};
        // Through a point at distance r (1 + delta) from the centre, perpendicular to the offset.
        const Vec3d d = rng.unit();
        const Vec3d w = normalize(cross(d, rng.unit()));
        const Vec3d touch = c + w * (r * (1 + near_zero(rng)));
        s.ray = {Vec3f(touch - d * (r * rng.uniform(1.5, 20))), Vec3f(d)};
    }
    return out;
}

std::vector<Sample<Triangle<float>>> triangle_samples(std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 602);
    std::vector<Sample<Triangle<float>>> out(n);
    for (auto& s : out) {
        const Vec3d a = rng.ball(1), b = rng.ball(1), c = rng.ball(1);
        s.shape = {Vec3f(a), Vec3f(b), Vec3f(c)};
        const Vec3d nrm = normalize(cross(b - a, c - a));
        // A point of the plane near the triangle (barycentrics in [-0.1, 1.1]).
        const double u = rng.uniform(-0.1, 1.1), v = rng.uniform(-0.1, 1.1 - u);
        const Vec3d p = a + (b - a) * u + (c - a) * v;
        const Vec3d in_plane = normalize(cross(nrm, rng.unit()));
        const double theta = near_zero(rng);
        const Vec3d d = in_plane * std::cos(theta) + nrm * std::sin(theta);
        s.ray = {Vec3f(p - d * rng.uniform(0.5, 3)), Vec3f(d)};
    }
    return out;
}

std::vector<Sample<Bounds3f>> box_samples(std::size_t n, std::uint64_t seed) {
    Sampler rng(seed, 603);
    std::vector<Sample<Bounds3f>> out(n);
    for (auto& s : out) {
        Vec3d lo, hi;
        for (std::size_t k = 0; k < 3; ++k) {
            const double x = rng.uniform(-5, 5), y = rng.uniform(-5, 5);
            lo[k] = std::min(x, y) - 0.05;
            hi[k] = std::max(x, y) + 0.05;
        }
        s.shape = {Vec3f(lo), Vec3f(hi)};
        const Vec3d size = hi - lo;
        // Near the plane of one face; half the rays also near an edge on that face (a second
        // coordinate near a face of its own), where the slab intervals nearly touch. Directions
        // (nearly) parallel to the first face, or random for the edge rays.
        const std::size_t a = rng.index(3);
        Vec3d p{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
        p[a] = (rng.index(2) ? hi[a] : lo[a]) + near_zero(rng) * size[a];
        Vec3d d = rng.unit();
        const bool edge = rng.index(2) == 0;
        if (edge) {
            const std::size_t b = (a + 1 + rng.index(2)) % 3;
            p[b] = (rng.index(2) ? hi[b] : lo[b]) + near_zero(rng) * size[b];
        }
        if (!edge || rng.index(2) == 0) {
            d[a] = rng.index(4) == 0 ? 0.0 : near_zero(rng);
        }
        d = normalize(d);
        Vec3f df(d);
        if (d[a] == 0.0) {
            df[a] = 0.0f;
        }
        s.ray = {Vec3f(p - d * rng.uniform(6, 12)), df};
    }
    return out;
}

/// Fills the exact answers, in parallel.
template <class Shape, class Oracle>
void judge(std::vector<Sample<Shape>>& samples, const Oracle& oracle) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              samples[i].truth = oracle(samples[i].shape, samples[i].ray);
                          }
                      });
}

template <class T>
Sphere<T> convert(const Sphere<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.radius)};
}
template <class T>
Triangle<T> convert(const Triangle<float>& s) {
    return {Vec3<T>(s.p0), Vec3<T>(s.p1), Vec3<T>(s.p2)};
}
template <class T>
Bounds3<T> convert(const Bounds3f& s) {
    return {Vec3<T>(s.lo), Vec3<T>(s.hi)};
}

/// One method in one precision over all samples: timed pass (repeated for >= 20 ms), then the
/// comparison with the exact answers.
template <class M, class Shape>
Row run_method(const std::string& family,
               const std::vector<Sample<Shape>>& samples,
               const std::string& note) {
    using T = typename M::Scalar;
    constexpr bool has_t = IntersectionMethod<M>;
    std::vector<typename M::Prepared> prepared;
    std::vector<Ray<T>> rays;
    for (const auto& s : samples) {
        prepared.push_back(M::prepare(convert<T>(s.shape)));
        rays.push_back(static_cast<Ray<T>>(s.ray));
    }
    std::vector<std::optional<PrimHit<T>>> res(rays.size());
    std::size_t passes = 0;
    const Stopwatch sw;
    do {
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if constexpr (has_t) {
                res[i] = M::intersect(prepared[i], rays[i]);
            } else {
                res[i] = M::occluded(prepared[i], rays[i])
                             ? std::optional<PrimHit<T>>(PrimHit<T>{T(0)})
                             : std::nullopt;
            }
        }
        ++passes;
    } while (sw.ns() < 2e7 && passes < 100);
    const double ns = sw.ns() / static_cast<double>(passes * std::max<std::size_t>(1, rays.size()));
    std::size_t false_hits = 0, false_misses = 0;
    ErrorStats err;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Truth& tr = samples[i].truth;
        const bool hit = res[i].has_value();
        false_hits += hit && !tr.hit ? 1 : 0;
        false_misses += !hit && tr.hit ? 1 : 0;
        if (has_t && hit && tr.hit) {
            err.add(static_cast<double>(res[i]->t), tr.t);
        }
    }
    Row row = make_row("grazing", family + "/" + std::string(M::name),
                       std::is_same_v<T, float> ? "float" : "double", rays.size(),
                       false_hits + false_misses, "false hits + misses", ns,
                       std::to_string(false_hits) + " false hits, " + std::to_string(false_misses) +
                           " false misses" + (note.empty() ? "" : "; " + note));
    err.fill(row);
    return row;
}

}  // namespace

std::vector<Row> run_grazing(const Options& opt) {
    std::vector<Row> rows;
    auto spheres = sphere_samples(opt.rays, opt.seed);
    judge(spheres, sphere_truth);
    auto tris = triangle_samples(opt.rays, opt.seed);
    judge(tris, triangle_truth);
    auto boxes = box_samples(opt.rays, opt.seed);
    judge(boxes, box_truth);
    std::size_t sphere_hits = 0, tri_hits = 0, box_hits = 0;
    for (const auto& s : spheres) {
        sphere_hits += s.truth.hit ? 1 : 0;
    }
    for (const auto& s : tris) {
        tri_hits += s.truth.hit ? 1 : 0;
    }
    for (const auto& s : boxes) {
        box_hits += s.truth.hit ? 1 : 0;
    }
    const auto share = [&](std::size_t hits) {
        return "exact hits " + std::to_string(hits) + " of " + std::to_string(opt.rays);
    };
    const auto each = [&]<class T>(std::type_identity<T>) {
        for_each_sphere_method<T>([&]<class M>() {
            rows.push_back(run_method<M>("sphere", spheres, share(sphere_hits)));
        });
        for_each_triangle_method<T>(
            [&]<class M>() { rows.push_back(run_method<M>("triangle", tris, share(tri_hits))); });
        for_each_aabb_method<T>(
            [&]<class M>() { rows.push_back(run_method<M>("aabb", boxes, share(box_hits))); });
    };
    each(std::type_identity<float>{});
    each(std::type_identity<double>{});
    // Group by family: sphere, triangle, aabb; float before double within a method.
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
        const auto rank = [](const Row& r) {
            return r.subject.rfind("sphere", 0) == 0
                       ? 0
                       : (r.subject.rfind("triangle", 0) == 0 ? 1 : 2);
        };
        return rank(a) != rank(b) ? rank(a) < rank(b) : a.subject < b.subject;
    });
    return rows;
}

}  // namespace rtlab::stab
