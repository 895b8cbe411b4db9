#pragma once
// What the stability cases share: a stopwatch, relative-error statistics, row assembly and tracing
// a whole batch through SceneTracer with any triangle method (occlusion-only methods answer
// through any-hit). Their seeded generator is base/sampler.h, shared with the cross-checks.

#include "base/sampler.h"
#include "intersect/triangle/methods.h"
#include "mesh/triangle_mesh.h"
#include "stability/stability.h"
#include "trace/scene_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rtlab::stab {

/// Wall-clock time since construction.
class Stopwatch {
public:
    /// Elapsed nanoseconds.
    double ns() const {
        return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start_)
            .count();
    }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// Relative errors |t - ref| / max(|ref|, DBL_MIN), reduced to the max and median of a Row.
class ErrorStats {
public:
    /// Record one pair of t values.
    void add(double t, double ref) {
        const double denom = std::max(std::abs(ref), std::numeric_limits<double>::min());
        errs_.push_back(std::abs(t - ref) / denom);
    }
    /// Writes max and median into row (leaves NaN when nothing was recorded).
    void fill(Row& row) const {
        if (errs_.empty()) {
            return;
        }
        std::vector<double> e = errs_;
        const auto mid = e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2);
        std::nth_element(e.begin(), mid, e.end());
        row.median_rel_t_err = *mid;
        row.max_rel_t_err = *std::max_element(e.begin(), e.end());
    }

private:
    std::vector<double> errs_;
};

/// A row with the counting fields filled.
inline Row make_row(std::string case_name,
                    std::string subject,
                    std::string precision,
                    std::size_t rays,
                    std::size_t failures,
                    std::string failure_kind,
                    double ns_per_ray,
                    std::string note = {}) {
    Row r;
    r.case_name = std::move(case_name);
    r.subject = std::move(subject);
    r.precision = std::move(precision);
    r.rays = rays;
    r.failures = failures;
    r.failure_kind = std::move(failure_kind);
    r.ns_per_ray = ns_per_ray;
    r.note = std::move(note);
    return r;
}

/// "name robust" or "name plain".
inline std::string robust_label(bool robust) {
    return robust ? "robust" : "plain";
}

/// Traces every ray through tracer: closest hit, or any hit (t = 0 on a hit) when
/// `occlusion_only`. Returns one Hit per ray (miss: prim == invalid_id).
inline std::vector<Hit> trace_all(const SceneTracer& tracer,
                                  const std::vector<Rayf>& rays,
                                  bool occlusion_only,
                                  TraversalStats* stats = nullptr) {
    std::vector<Hit> hits(rays.size());
    if (occlusion_only) {
        std::vector<std::uint32_t> blockers(rays.size());
        tracer.occluded(rays, blockers, stats);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hits[i] = blockers[i] == invalid_id ? Hit{} : Hit{0.0f, 0.0f, 0.0f, blockers[i]};
        }
    } else {
        tracer.intersect(rays, hits, stats);
    }
    return hits;
}

}  // namespace rtlab::stab
