#pragma once
// Runtime choice of acceleration structure: a std::variant over the structure types of one list
// (AccelTypes) plus one registry table (accel/registry.cpp: name, description, parameters, build
// function per row) that feeds the command line, the tests, the benchmarks and the sweeps. The
// choice is made once per batch with std::visit, never per ray; every instantiation over the
// structure types (the tracer's, the benchmarks') is generated from AccelTypes.
//
// Adding a builder: one accel/<kind>/build_<name>.cpp and one row in accel/registry.cpp.
// Adding a structure or node layout: its header (and .cpp), one entry in AccelTypes below, and
// its row(s) in accel/registry.cpp. docs/architecture.md, "How to add ...", has the details.

#include "accel/accel.h"
#include "accel/brute_force.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/pair_bvh.h"
#include "accel/bvh/wide_bvh.h"
#include "accel/grid/grid.h"
#include "accel/grid/two_level_grid.h"
#include "accel/kdtree/kdtree.h"
#include "accel/spec.h"

#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

namespace rtlab {

/// Every structure type (node layout) a registry row can build.
using AccelTypes = std::tuple<BruteForce,
                              Bvh,
                              PairBvh,
                              WideBvh<4>,
                              WideBvh<8>,
                              WideBvh<16>,
                              KdTree,
                              Grid,
                              TwoLevelGrid>;

namespace detail {
template <class List>
struct VariantOf;
template <class... As>
struct VariantOf<std::tuple<As...>> {
    static_assert((Accel<As> && ...), "every AccelTypes entry satisfies the Accel concept");
    using type = std::variant<As...>;
};
}  // namespace detail

/// Any built acceleration structure.
using AnyAccel = typename detail::VariantOf<AccelTypes>::type;

/// One registry row: a structure built by one builder, with the parameters it accepts.
struct AccelEntry {
    std::string_view name;          ///< spec name, e.g. "bvh:binned"
    std::string_view description;   ///< one line for `rtlab list` and reports
    std::vector<ParamSpec> params;  ///< the keys a spec may set, in canonical order
    AnyAccel (*build)(const BuildInput&, const AccelSpec&);  ///< builds with the spec's values
};

/// Every registered structure/builder, in a fixed order (brute force first).
std::span<const AccelEntry> accel_registry();

/// Whether a tracer keeps its primitives in the structure's leaf-slot order and tests whole leaves
/// (the spec's `leaves=soa`, the default; also for rows without the key): a tracer's choice,
/// which the structures do not store.
bool slot_ordered_leaves(const AccelSpec& s);

/// Parameter variants that reports run beside the rows' defaults as layouts of their own (the
/// targets benchmark suite, the stability suite's leak cases): specs, not registry rows.
std::span<const std::string_view> accel_variants();

/// The structure used where none is named (TraceSetup, `rtlab trace` and `rtlab render`, the
/// secondary rays of generated ray sets): the binned SAH BVH's registry row.
inline constexpr std::string_view default_accel = "bvh:binned";

/// The row called `name` (a bare name, no parameters), or nullptr.
const AccelEntry* find_accel(std::string_view name);

/// The spec of row `e` with every parameter at its default.
AccelSpec default_spec(const AccelEntry& e);

/// Builds the structure a parsed spec names.
AnyAccel build_accel(const AccelSpec& spec, const BuildInput& in);

/// Parses `spec` (see parse_accel_spec, which throws std::invalid_argument on a bad spec) and
/// builds it.
AnyAccel build_accel(std::string_view spec, const BuildInput& in);

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
