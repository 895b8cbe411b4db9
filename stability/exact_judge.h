#pragma once
// Judging intersection methods on one-shape-one-ray samples against exact answers
// (crosscheck/exact.h): hit/miss disagreements, NaN results, relative error of t, ns per ray.
// Shared by the far_small, centres, needles and implicit cases.

#include "intersect/method.h"
#include "stability/case_util.h"
#include "stability/stability.h"

#include <cmath>
#include <cstddef>
#include <string>
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
