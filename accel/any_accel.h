#pragma once
// Runtime choice of acceleration structure: a std::variant of every structure plus one registry
// table (name, description, build function) that feeds the command line, the tests and the
// benchmarks. The choice is made once per batch with std::visit, never per ray.
//
// Adding a structure: include its header here, add it to AnyAccel, add one row per builder to
// the table in any_accel.cpp. accel_info, accel_validate and visit_accel need no change.

#include "accel/accel.h"
#include "accel/brute_force.h"
#include "accel/bvh/bvh.h"
#include "accel/grid/grid.h"
#include "accel/kdtree/kdtree.h"

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace rtlab {

/// Any built acceleration structure.
using AnyAccel = std::variant<BruteForce, Bvh, KdTree, Grid>;

/// One registry row: a structure with one builder configuration.
struct AccelEntry {
    std::string_view name;                 ///< command-line name, e.g. "bvh:binned"
    std::string_view description;          ///< one line for --help and reports
    AnyAccel (*build)(const BuildInput&);  ///< builds with this row's configuration
};

/// Every registered structure/builder, in a fixed order (brute force first).
std::span<const AccelEntry> accel_registry();

/// The row called `name`, or nullptr.
const AccelEntry* find_accel(std::string_view name);

/// Builds the structure called `name`; throws std::invalid_argument listing the known names
/// when there is none.
AnyAccel build_accel(std::string_view name, const BuildInput& in);

/// Calls f once with the concrete structure held by a (a const reference). Put the whole batch
/// loop inside f so the dispatch happens once per batch, e.g.
/// `visit_accel(a, [&](const auto& s) { for (Rayf& r : rays) s.intersect(r, hit_fn); });`
template <class F>
decltype(auto) visit_accel(const AnyAccel& a, F&& f) {
    return std::visit(std::forward<F>(f), a);
}

/// info() of the held structure.
AccelInfo accel_info(const AnyAccel& a);

/// validate() of the held structure (empty when every invariant holds).
std::string accel_validate(const AnyAccel& a);

/// bounds() of the held structure.
Bounds3f accel_bounds(const AnyAccel& a);

}  // namespace rtlab
