#pragma once
// The numerical-stability suite: stiff and extreme cases (leaks through shared edges, degenerate
// and grazing rays, far and small geometry, self-intersection of secondary rays, tangent roots).
// Every case returns rows of "subject x precision: rays, failures, error of t, ns per ray", which
// `rtlab stability` writes as docs/stability.md and tests/stability_*_test.cpp assert on.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::stab {

/// How much to run. Tests use the defaults (>= 10,000 rays); the report may use more.
struct Options {
    std::size_t rays = 10000;  ///< rays per subject and precision (where rays are involved)
    std::uint64_t seed = 1;    ///< seeds shapes and rays; same seed, same rays
};

/// One line of the report: one subject (method, method + structure, offset policy, ...) in one
/// precision on one case.
struct Row {
    std::string case_name;     ///< e.g. "watertight/inside"
    std::string subject;       ///< e.g. "watertight + bvh:binned robust"
    std::string precision;     ///< "float", "double", or "-" when it does not apply
    std::size_t rays = 0;      ///< rays (or tests) run
    std::size_t failures = 0;  ///< rays that failed the case's property
    std::string
        failure_kind;  ///< what a failure is: "leaks", "false hits", "re-intersections", ...
    double max_rel_t_err = std::numeric_limits<double>::quiet_NaN();     ///< NaN: not measured
    double median_rel_t_err = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not measured
    double ns_per_ray = std::numeric_limits<double>::quiet_NaN();        ///< single thread
    std::string note;  ///< cause of the failures when known, or anything a reader must know
    /// The case classifies (some of) the failures as a defect of rtlab, not of the method under
    /// test (e.g. rays lost by robust traversal); every test of the suite fails on such a row.
    bool defect = false;
};

/// One case of the suite.
struct Case {
    std::string_view name;         ///< e.g. "watertight"; accepted by `rtlab stability --case`
    std::string_view description;  ///< one sentence for the report
    std::vector<Row> (*run)(const Options& opt);
};

/// Every case, in report order.
std::span<const Case> cases();

/// The case called `name`, or nullptr.
const Case* find_case(std::string_view name);

}  // namespace rtlab::stab
