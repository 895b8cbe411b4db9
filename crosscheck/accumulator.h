#pragma once
// Turns per-ray (method answer, oracle answer) pairs into a Row: agreement counts and the
// relative error of t where both say hit. A ray agrees only when its answer is the exact one:
// same hit/miss and, for a hit, t within the precision's relative tolerance (t_tolerance<T>());
// a hit on both sides with t outside it (or NaN) is `wrong_t`: the method found another surface.

#include "crosscheck/crosscheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace rtlab::xcheck {

/// Relative t tolerance of a hit that counts as the exact one: 2^-10 (~9.8e-4) in float and
/// 2^-20 (~9.5e-7) in double. Both sit far above rounding in t (a few ulps; sqrt(eps) = 3.5e-4
/// and 1.5e-8 at a near-double root of a tangent ray) and far below the distance to another
/// surface of the shapes checked (the far side of a closed mesh is at a relative t error near 1).
template <class T>
constexpr double t_tolerance() {
    return std::is_same_v<T, float> ? 0x1p-10 : 0x1p-20;
}

/// Collects the comparison of one method/precision/set against the oracle.
class Accumulator {
public:
    /// t_tol: the relative t tolerance (t_tolerance<T>() of the method's precision). has_t is
    /// false for hit/no-hit methods (Segura-Feito): agreement is then hit/miss only, and the t
    /// errors and wrong_t are reported as NaN / "-".
    explicit Accumulator(double t_tol, bool has_t = true) : t_tol_(t_tol), has_t_(has_t) {}

    /// Record one ray: whether each side hit, and their t (ignored on a miss).
    void add(bool method_hit, bool oracle_hit, double t_method, double t_oracle) {
        ++rays_;
        if (method_hit != oracle_hit) {
            ++(method_hit ? false_hit_ : false_miss_);
            return;
        }
        if (!has_t_ || !method_hit) {
            ++agree_;
            return;
        }
        const double denom = std::max(std::abs(t_oracle), std::numeric_limits<double>::min());
        double err = std::abs(t_method - t_oracle) / denom;
        if (std::isnan(err)) {
            err = std::numeric_limits<double>::infinity();  // a NaN t is never the exact answer
        }
        errs_.push_back(err);
        ++(err <= t_tol_ ? agree_ : wrong_t_);
    }

    /// Merge another accumulator (for the "all" row built from per-set rows).
    void merge(const Accumulator& o) {
        rays_ += o.rays_;
        agree_ += o.agree_;
        wrong_t_ += o.wrong_t_;
        false_hit_ += o.false_hit_;
        false_miss_ += o.false_miss_;
        errs_.insert(errs_.end(), o.errs_.begin(), o.errs_.end());
    }

    /// The finished row; ns_per_test is the caller's timing.
    Row row(std::string prim,
            std::string method,
            std::string precision,
            std::string set,
            double ns_per_test) const {
        Row r;
        r.prim = std::move(prim);
        r.method = std::move(method);
        r.precision = std::move(precision);
        r.set = std::move(set);
        r.rays = rays_;
        r.agree = agree_;
        r.wrong_t = wrong_t_;
        r.has_t = has_t_;
        r.t_tol = t_tol_;
        r.false_hit = false_hit_;
        r.false_miss = false_miss_;
        r.ns_per_test = ns_per_test;
        if (!has_t_) {
            r.max_rel_t_err = r.median_rel_t_err = std::numeric_limits<double>::quiet_NaN();
        } else if (!errs_.empty()) {
            std::vector<double> e = errs_;
            const auto mid = e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2);
            std::nth_element(e.begin(), mid, e.end());
            r.median_rel_t_err = *mid;
            r.max_rel_t_err = *std::max_element(e.begin(), e.end());
        }
        return r;
    }

private:
    double t_tol_;
    bool has_t_;
    std::size_t rays_ = 0, agree_ = 0, wrong_t_ = 0, false_hit_ = 0, false_miss_ = 0;
    std::vector<double> errs_;
};

/// Which of a kind's methods to run: all when `wanted` is empty, else exactly those, in order.
/// Throws std::invalid_argument naming an unknown method and the known ones.
inline std::vector<std::string> select_methods(const std::vector<std::string>& known,
                                               const std::vector<std::string>& wanted,
                                               std::string_view prim) {
    if (wanted.empty()) {
        return known;
    }
    for (const std::string& w : wanted) {
        if (std::find(known.begin(), known.end(), w) == known.end()) {
            std::string list;
            for (const std::string& k : known) {
                list += (list.empty() ? "" : ", ") + k;
            }
            throw std::invalid_argument("unknown " + std::string(prim) + " method '" + w +
                                        "' (known: " + list + ")");
        }
    }
    return wanted;
}

}  // namespace rtlab::xcheck
