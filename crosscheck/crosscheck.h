#pragma once
// Cross-checks of intersection methods against CGAL's exact predicates: for one primitive kind,
// every method in float and double traces the same seeded ray sets, and each answer is compared
// with the exact one. The rows are the "error against run time" table of `rtlab crosscheck`.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::xcheck {

/// What to run: which methods (empty = all), which precisions, how many rays per ray set.
struct Options {
    std::vector<std::string> methods;  ///< method names; empty means every method of the kind
    bool f32 = true;                   ///< run the float instantiation
    bool f64 = true;                   ///< run the double instantiation
    std::size_t rays = 100000;         ///< rays per method and precision (all sets together)
    std::uint64_t seed = 1;            ///< seeds shapes and rays; same seed, same rays
    bool by_set = false;               ///< one row per ray set as well as the total row
};

/// One line of the table: a method in one precision against the exact oracle.
struct Row {
    std::string prim;             ///< primitive kind: triangle, polygon, aabb, obb, sphere, ...
    std::string method;           ///< method name as accepted by --method
    std::string precision;        ///< "float" or "double"
    std::string set = "all";      ///< ray set name, "all" for the total
    std::size_t rays = 0;         ///< rays traced
    std::size_t agree = 0;        ///< rays answered exactly: the oracle's hit/miss and, for a
                                  ///< hit, t within t_tol relative (hit/miss only without t)
    std::size_t wrong_t = 0;      ///< both hit, t off by more than t_tol (another surface) or NaN
    std::size_t false_hit = 0;    ///< method hit, oracle says miss
    std::size_t false_miss = 0;   ///< method missed, oracle says hit
    bool has_t = true;            ///< the method reports t (false: hit/no-hit only)
    double t_tol = 0;             ///< the relative t tolerance of agree (t_tolerance<T>())
    double max_rel_t_err = 0;     ///< over rays both call a hit; NaN when the method has no t
    double median_rel_t_err = 0;  ///< same, median
    double ns_per_test = 0;       ///< one ray-primitive test on set-up ray data, single thread
    bool has_setup = false;       ///< the method has per-ray set-up (precompute)
    double setup_ns_per_ray = 0;  ///< its set-up per ray, single thread (0 without set-up)
};

/// One primitive kind's checker.
struct PrimCheck {
    std::string_view prim;                        ///< name accepted by --prim
    std::vector<std::string> (*methods)();        ///< method names of this kind
    std::vector<Row> (*run)(const Options& opt);  ///< runs the selected methods; throws on bad
                                                  ///< method names (std::invalid_argument)
};

/// Every primitive kind, in the order of the --prim help text.
std::span<const PrimCheck> prim_checks();

/// The checker for a kind, or nullptr.
const PrimCheck* find_prim_check(std::string_view prim);

}  // namespace rtlab::xcheck
