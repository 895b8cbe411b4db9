#pragma once
// Judging intersection methods on one-shape-one-ray samples against exact answers
// (crosscheck/exact.h): hit/miss disagreements, NaN results, relative error of t, ns per ray.
// Shared by the far_small, centres, needles, implicit and cone cases.

#include "crosscheck/exact.h"
#include "intersect/method.h"
#include "intersect/sphere/sphere.h"
#include "stability/case_util.h"
#include "stability/stability.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <tbb/parallel_for.h>
#include <type_traits>
#include <vector>

namespace rtlab::stab {

/// The exact answer for one sample; `defined` is false where no rounding method can be expected
/// to agree (the ray meets an edge or vertex exactly, or lies in a triangle's plane).
struct ExactTruth {
    bool hit = false;
    double t = 0;
    bool defined = true;
};

/// An exact root as an answer (always defined).
inline ExactTruth to_truth(const xcheck::ExactRoot& e) {
    return {e.hit, e.t, true};
}

/// An exact triangle answer (undefined where the ray meets the boundary or lies in the plane).
inline ExactTruth to_truth(const xcheck::ExactTriangleHit& e) {
    return {e.hit, e.t, !e.boundary};
}

/// The exact answers of samples 0 .. n-1, computed in parallel: exact(i) is sample i's
/// xcheck::ExactRoot or xcheck::ExactTriangleHit.
template <class Exact>
std::vector<ExactTruth> exact_truths(std::size_t n, const Exact& exact) {
    std::vector<ExactTruth> out(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) { out[i] = to_truth(exact(i)); });
    return out;
}

/// How many of the answers are hits.
inline std::size_t exact_hit_count(const std::vector<ExactTruth>& truth) {
    std::size_t n = 0;
    for (const ExactTruth& t : truth) {
        n += t.hit ? 1 : 0;
    }
    return n;
}

/// v rounded to precision T and back (exactly).
template <class T>
Vec3d round_to(const Vec3d& v) {
    return Vec3d(Vec3<T>(v));
}

/// Rays generated in double (already rounded to T) in precision T, for judge().
template <class T>
std::vector<Ray<T>> rays_in(const std::vector<Rayd>& rays_d) {
    std::vector<Ray<T>> rays;
    rays.reserve(rays_d.size());
    for (const Rayd& r : rays_d) {
        rays.push_back(static_cast<Ray<T>>(r));
    }
    return rays;
}

/// Spheres and rays of one sample set, already rounded to the precision under test (stored in
/// double, exactly), with the exact answers (set by add_sphere_truth).
struct SphereSamples {
    std::vector<Sphered> spheres;
    std::vector<Rayd> rays;
    std::vector<ExactTruth> truth;
};

/// Sets s.truth to the exact sphere answer of every sample.
inline void add_sphere_truth(SphereSamples& s) {
    s.truth = exact_truths(s.rays.size(), [&](std::size_t i) {
        return xcheck::exact_sphere_root(s.spheres[i].center, s.spheres[i].radius, s.rays[i]);
    });
}

/// "float" or "double".
template <class T>
std::string precision_of() {
    return std::is_same_v<T, float> ? "float" : "double";
}

/// What one method did on a sample set.
struct MethodTally {
    std::size_t rays = 0;        ///< samples tested
    std::size_t false_miss = 0;  ///< exact hit, method missed (defined samples only)
    std::size_t false_hit = 0;   ///< exact miss, method hit (defined samples only)
    std::size_t undefined = 0;   ///< samples left out of the hit/miss comparison
    std::size_t nan = 0;         ///< hits whose t, u or v is not finite
    ErrorStats err;              ///< relative t error where both hit
    double ns = 0;               ///< ns per ray of a single-threaded timed pass

    /// Wrong hit/miss answers plus non-finite hits.
    std::size_t failures() const { return false_miss + false_hit + nan; }
};

/// Runs method M on rays[i] against shape_at(i) (a M::Shape), compares with truth[i] and times a
/// second pass. Occlusion-only methods are judged on hit/miss alone. When `answers` is given it
/// receives 1 per hit and 0 per miss.
template <class M, class ShapeAt>
MethodTally judge(const std::vector<Ray<typename M::Scalar>>& rays,
                  const std::vector<ExactTruth>& truth,
                  const ShapeAt& shape_at,
                  std::vector<char>* answers = nullptr) {
    using T = typename M::Scalar;
    std::vector<typename M::Prepared> prepared;
    prepared.reserve(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        prepared.push_back(M::prepare(shape_at(i)));
    }
    MethodTally out;
    out.rays = rays.size();
    if (answers) {
        answers->assign(rays.size(), 0);
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        bool hit = false;
        T t = 0;
        if constexpr (IntersectionMethod<M>) {
            if (const auto h = M::intersect(prepared[i], rays[i])) {
                hit = true;
                t = h->t;
                if (!std::isfinite(h->t) || !std::isfinite(h->u) || !std::isfinite(h->v)) {
                    ++out.nan;
                    continue;
                }
            }
        } else {
            hit = M::occluded(prepared[i], rays[i]);
        }
        if (answers) {
            (*answers)[i] = hit ? 1 : 0;
        }
        if (!truth[i].defined) {
            ++out.undefined;
            continue;
        }
        if (hit && !truth[i].hit) {
            ++out.false_hit;
        } else if (!hit && truth[i].hit) {
            ++out.false_miss;
        } else if (hit && IntersectionMethod<M>) {
            out.err.add(static_cast<double>(t), truth[i].t);
        }
    }
    const Stopwatch sw;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if constexpr (IntersectionMethod<M>) {
            hits += M::intersect(prepared[i], rays[i]).has_value() ? 1 : 0;
        } else {
            hits += M::occluded(prepared[i], rays[i]) ? 1 : 0;
        }
    }
    out.ns = rays.empty() ? 0.0 : sw.ns() / static_cast<double>(rays.size());
    volatile std::size_t keep = hits;
    static_cast<void>(keep);
    return out;
}

/// The report row of a tally: failures are false misses + false hits + non-finite hits.
inline Row tally_row(std::string case_name,
                     std::string subject,
                     std::string precision,
                     const MethodTally& t,
                     const std::string& note = {}) {
    std::string n = "false misses " + std::to_string(t.false_miss) + ", false hits " +
                    std::to_string(t.false_hit);
    if (t.nan != 0) {
        n += ", non-finite hits " + std::to_string(t.nan);
    }
    if (t.undefined != 0) {
        n += ", " + std::to_string(t.undefined) + " boundary rays not judged";
    }
    if (!note.empty()) {
        n += "; " + note;
    }
    Row r = make_row(std::move(case_name), std::move(subject), std::move(precision), t.rays,
                     t.failures(), "false misses + false hits", t.ns, n);
    t.err.fill(r);
    return r;
}

}  // namespace rtlab::stab
