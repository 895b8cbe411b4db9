// The registry: one row per structure and builder. A row names the structure, describes it in one
// line, declares the parameters a spec may set (each declared once, bound to its Config member,
// defaults taken from the Config: accel/registry_fields.h) and builds from a parsed spec. Adding a
// binary BVH builder: its own accel/bvh/build_<name>.cpp with one free function, declared here,
// and its entry in binary_builders, which makes both its row and its `from=` choice.
#include "accel/any_accel.h"
#include "accel/cost_model.h"
#include "accel/registry_fields.h"
#include "base/thread_arena.h"

#include <stdexcept>

namespace rtlab {

// The builder functions, one .cpp each (the row below is the only other place that names them).
Bvh build_bvh_median(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
Bvh build_bvh_binned_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
Bvh build_bvh_sweep_sah(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
Bvh build_bvh_lbvh(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
Bvh build_bvh_binned_parallel(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
Bvh build_bvh_sbvh(const BuildInput& in, const Bvh::Config& cfg, std::uint32_t threads);
KdTree build_kdtree_sah(const BuildInput& in, const KdTree::Config& cfg);
KdTree build_kdtree_median(const BuildInput& in, const KdTree::Config& cfg);
Grid build_grid_uniform(const BuildInput& in, const GridConfig& cfg, std::uint32_t threads);
TwoLevelGrid build_grid_two_level(const BuildInput& in,
                                  const TwoLevelGridConfig& cfg,
                                  std::uint32_t threads);

namespace {

using registry::choice;
using registry::Choice;
using registry::config_from;
using registry::Field;
using registry::field;

// Parameters shared by several rows; each default is the Config's own.
const Bvh::Config bvh_default{};
const KdTree::Config kd_default{};
const GridConfig grid_default{};
const TwoLevelGridConfig grid2_default{};
constexpr double cost_max = 1e6;

const Field<Bvh::Config> max_leaf = field<&Bvh::Config::max_leaf_size>(
    integer_param("max_leaf",
                  bvh_default.max_leaf_size,
                  1,
                  BvhNode::max_prim_count,
                  "most primitives in one leaf (a larger range is always split)"));
const Field<Bvh::Config> bins = field<&Bvh::Config::bin_count>(
    integer_param("bins",
                  bvh_default.bin_count,
                  1,
                  1024,
                  "bins per axis over the centroid bounds (1 = object median)"));
const Field<Bvh::Config> bvh_ct =
    field<&Bvh::Config::traversal_cost>(real_param("ct",
                                                   static_cast<double>(bvh_default.traversal_cost),
                                                   0,
                                                   cost_max,
                                                   "SAH cost of one node visit"));
const Field<Bvh::Config> bvh_ci = field<&Bvh::Config::intersection_cost>(
    real_param("ci",
               static_cast<double>(bvh_default.intersection_cost),
               1e-3,
               cost_max,
               "SAH cost of one primitive test"));
const Field<Bvh::Config> sah_block = field<&Bvh::Config::sah_block>(integer_param(
    "block",
    bvh_default.sah_block,
    1,
    64,
    "the SAH counts a range's primitives in started blocks of this many (Embree's sahBlockSize)"));
const Field<Bvh::Config> morton_bits = field<&Bvh::Config::morton_bits>(
    integer_param("morton_bits", bvh_default.morton_bits, 1, 10, "Morton code bits per axis"));
const ParamSpec threads = build_only(
    integer_param("threads",
                  0,
                  0,
                  256,
                  "TBB threads of the build (0: all allowed); the tree is the same for any"));
const Field<KdTree::Config> kd_ct = field<&KdTree::Config::traversal_cost>(
    real_param("ct",
               static_cast<double>(kd_default.traversal_cost),
               0,
               cost_max,
               "K_T: SAH cost of one inner-node step"));
const Field<KdTree::Config> kd_ci = field<&KdTree::Config::intersection_cost>(
    real_param("ci",
               static_cast<double>(kd_default.intersection_cost),
               1e-3,
               cost_max,
               "K_I: SAH cost of one primitive test"));
const Field<KdTree::Config> empty_bonus = field<&KdTree::Config::empty_bonus>(
    real_param("empty_bonus",
               static_cast<double>(kd_default.empty_bonus),
               0,
               0.99,
               "split cost scaled by (1 - bonus) when one side is empty"));
const Field<KdTree::Config> max_depth =
    field<&KdTree::Config::max_depth>(integer_param("max_depth",
                                                    kd_default.max_depth,
                                                    0,
                                                    KdTree::depth_limit,
                                                    "deepest leaf; 0 = 8 + 1.3 log2 N (pbrt)"));
const Field<KdTree::Config> min_leaf = field<&KdTree::Config::min_leaf_size>(
    integer_param("min_leaf",
                  kd_default.min_leaf_size,
                  1,
                  1024,
                  "nodes with at most this many primitives become leaves"));
const Field<KdTree::Config> perfect = field<&KdTree::Config::perfect_splits>(
    integer_param("perfect",
                  kd_default.perfect_splits ? 1 : 0,
                  0,
                  1,
                  "1: perfect splits (straddling triangles clipped to each side; slower build), "
                  "0: boxes cut at the plane"));
const Field<KdTree::Config> kd_threads = field<&KdTree::Config::threads>(threads);
const Field<KdTree::Config> kd_traversal = field<&KdTree::Config::traversal>(
    choice<KdTraversal>("traversal",
                        "havran",
                        {{"havran", KdTraversal::havran}, {"tvalue", KdTraversal::tvalue}},
                        "havran: TA^B_rec with entry/exit points (Havran 2000); tvalue: pbrt's "
                        "(node, t_enter, t_exit) stack"));
// Leaves as SoA data for the tracers' SIMD kernels, or primitive ids (kd-trees and the layouts).
const Choice<bool> leaves = choice<bool>("leaves",
                                         "soa",
                                         {{"soa", true}, {"ids", false}},
                                         "soa: tracers test whole leaves with SIMD kernels on "
                                         "slot-ordered data; ids: one primitive id at a time");
// A kd-tree is the same for both: only a tracer reads it (slot_ordered_leaves).
const ParamSpec kd_leaves = tracer_only(leaves.param);
const Field<GridConfig> density =
    field<&GridConfig::density>(real_param("density",
                                           static_cast<double>(grid_default.density),
                                           1e-3,
                                           1e3,
                                           "lambda: target cells per primitive (Woo)"));
const Field<GridConfig> max_res = field<&GridConfig::max_res>(
    integer_param("max_res", grid_default.max_res, 1, 1024, "most cells along one axis"));
const Field<TwoLevelGridConfig> top_density = field<&TwoLevelGridConfig::top_density>(
    real_param("top_density",
               static_cast<double>(grid2_default.top_density),
               1e-4,
               1e2,
               "lambda_1: top-grid cells per primitive (Woo)"));
const Field<TwoLevelGridConfig> leaf_density = field<&TwoLevelGridConfig::leaf_density>(
    real_param("leaf_density",
               static_cast<double>(grid2_default.leaf_density),
               1e-3,
               1e2,
               "lambda_2: cells per primitive of each sub-grid (Woo)"));
const Field<TwoLevelGridConfig> grid2_max_res = field<&TwoLevelGridConfig::max_res>(integer_param(
    "max_res", grid2_default.max_res, 1, 1024, "most cells along one axis, either level"));

std::uint32_t threads_of(const AccelSpec& s) {
    return static_cast<std::uint32_t>(s.value_or(threads.key, 0));
}

Bvh::Config bvh_config(const AccelSpec& s) {
    return config_from<Bvh::Config>(s,
                                    {&max_leaf, &bins, &bvh_ct, &bvh_ci, &morton_bits, &sah_block});
}

KdTree::Config kd_config(const AccelSpec& s) {
    return config_from<KdTree::Config>(s, {&kd_ct, &kd_ci, &empty_bonus, &max_depth, &min_leaf,
                                           &perfect, &kd_threads, &kd_traversal});
}

GridConfig grid_config(const AccelSpec& s) {
    return config_from<GridConfig>(s, {&density, &max_res});
}

TwoLevelGridConfig grid2_config(const AccelSpec& s) {
    return config_from<TwoLevelGridConfig>(s, {&top_density, &leaf_density, &grid2_max_res});
}

/// A row's build function: the builder B called with the Config the spec describes.
template <auto B, auto ToConfig>
AnyAccel row(const BuildInput& in, const AccelSpec& s) {
    return B(in, ToConfig(s));
}

/// A parallel builder's row: B also gets the spec's `threads`.
template <auto B, auto ToConfig>
AnyAccel threaded_row(const BuildInput& in, const AccelSpec& s) {
    return B(in, ToConfig(s), threads_of(s));
}

ParamSpec with_default(ParamSpec p, double value) {
    p.default_value = value;
    return p;
}
ParamSpec with_max(ParamSpec p, double value) {
    p.max = value;
    return p;
}
// The SAH builders (bvh:binned, bvh:pbinned, bvh:sweep) and the wide layouts' source trees default
// to leaves of up to 8 with ct 4, not the Config's 4 and 1: a node visit costs about four triangle
// tests here. The wide layouts' SIMD leaf kernel tests up to 8 triangles for about the price of
// one, and sweeps/bvh8-leaves.json measured them 1.2-1.3x faster on the tessellated flake (analytic
// spheres: unchanged), with leaf and node memory less than half; the binary SAH rows traced SF 4 a
// median 1.08x (tessellated) and 1.14x (analytic) as fast as with 4 and 1 (`rtlab trace --threads 1
// --repeat 5`, 42 alternating pairs), and built the mesh in 25-45% less time (docs/results.md,
// "Structures: speed, memory, build time (against Embree)").
const ParamSpec sah_max_leaf = with_default(max_leaf.param, 8);
const ParamSpec sah_ct = with_default(bvh_ct.param, 4);

// The binned SAH builders take the same parameters.
const std::vector<ParamSpec> binned_params{sah_max_leaf, bins.param,      sah_ct,
                                           bvh_ci.param, sah_block.param, threads};

// The binary BVH builders: each is a row of its own ("bvh:<name>") and one of the layout rows'
// `from=` choices (<name>), so the two lists are one.
struct BinaryBuilder {
    AccelEntry row;
    Bvh (*build)(const BuildInput&, const Bvh::Config&, std::uint32_t);
};

/// The builder B as a row and a source of layout rows.
template <auto B>
BinaryBuilder binary(std::string_view name,
                     std::string_view description,
                     std::vector<ParamSpec> params) {
    return {{name, description, std::move(params), &threaded_row<B, bvh_config>}, B};
}

const BinaryBuilder binary_builders[] = {
    binary<build_bvh_median>("bvh:median",
                             "binary BVH, object median on the largest centroid axis",
                             {max_leaf.param, threads}),
    binary<build_bvh_binned_sah>("bvh:binned", "binary BVH, binned SAH (Wald 2007)", binned_params),
    binary<build_bvh_binned_parallel>(
        "bvh:pbinned",
        "binary BVH, binned SAH on all axes in one pass (min(bins, 4 + n/20) bins for n "
        "primitives), parallel with TBB, deterministic",
        binned_params),
    binary<build_bvh_sweep_sah>("bvh:sweep",
                                "binary BVH, full-sweep SAH (MacDonald & Booth 1990)",
                                {sah_max_leaf, sah_ct, bvh_ci.param, sah_block.param, threads}),
    binary<build_bvh_sbvh>(
        "bvh:sbvh",
        "binary BVH, binned SAH with spatial splits (Stich et al. 2009; 2 bins or more): a "
        "primitive may be cut into several leaves; parallel with TBB, deterministic",
        binned_params),
    binary<build_bvh_lbvh>("bvh:lbvh",
                           "binary BVH, Morton-code radix tree (Karras 2012)",
                           {max_leaf.param, morton_bits.param, threads}),
};

/// `from`: the choice among binary_builders by their names after "bvh:" (default pbinned).
Choice<const BinaryBuilder*> binary_builder_choice() {
    Choice<const BinaryBuilder*> c;
    std::vector<std::string_view> names;
    std::size_t default_index = 0;
    for (const BinaryBuilder& b : binary_builders) {
        const std::string_view name = b.row.name.substr(b.row.name.find(':') + 1);
        default_index = name == "pbinned" ? names.size() : default_index;
        names.push_back(name);
        c.values.push_back(&b);
    }
    c.param = choice_param("from", default_index, std::move(names),
                           "the binary BVH builder whose tree is converted");
    return c;
}

const Choice<const BinaryBuilder*> from = binary_builder_choice();

/// The binary tree a layout row converts: built by the builder its `from` parameter names.
Bvh source_bvh(const BuildInput& in, const AccelSpec& s) {
    return from.of(s)->build(in, bvh_config(s), threads_of(s));
}

// Leaves starting whole 4-slot groups of the SoA leaf data (accel/bvh/bvh.h align_leaf_slots):
// against packed leaves (`leaf_align=1`, `rtlab trace --threads 1 --repeat 9`), bvh8 on the
// tessellated SF 4 (1.65M triangles, 20% more slots) traced shadow rays 1.06x as fast, diffuse
// 1.02-1.07x, primary 0.99-1.01x; on the analytic SF 4 primary 1.015x, diffuse 1.04x; bvh:pair
// 1.00-1.035x.
const ParamSpec leaf_align = only_with(integer_param("leaf_align",
                                                     4,
                                                     1,
                                                     64,
                                                     "every leaf starts at a multiple of this many "
                                                     "slots (padding between leaves); 1 packs"),
                                       leaves.param.key,
                                       {"soa"});

// Children larger box first: any-hit traversal visits them in slot order (accel/bvh/bvh.h
// ChildOrder). Against `order=build` on the tessellated SF 4's shadow rays (`rtlab trace --any-hit
// --threads 1 --repeat 9`): bvh:pair 1.05-1.07x as fast with 2% fewer nodes per ray, bvh8 within
// noise.
const Choice<ChildOrder> child_order =
    choice<ChildOrder>("order",
                       "area",
                       {{"area", ChildOrder::area}, {"build", ChildOrder::build}},
                       "area: a node's children by surface area, largest first (any-hit visits "
                       "them in that order); build: as the source tree holds them");

/// The `from` builder's tree with its leaves aligned as the spec asks (only for SoA leaves).
Bvh aligned_source(const BuildInput& in, const AccelSpec& s) {
    const auto align = static_cast<std::uint32_t>(leaves.of(s) ? s.value(leaf_align.key) : 1);
    return align_leaf_slots(source_bvh(in, s), align);
}

// The least-area collapse by default: the same build time as the greedy one (1.65M triangles, 1
// thread: bvh8 417 against 419 ms, bvh16 411 against 402), fewer node visits, and 0.99-1.16x the
// greedy trees' speed paired against Embree medium on the tessellated SF 4 and the analytic SF 4
// and SF 5 flakes (`rtlab_bench --suite targets`; docs/results.md, "Structures: speed, memory,
// build time (against Embree)").
const Choice<WideCollapse> collapse =
    choice<WideCollapse>("collapse",
                         "sah",
                         {{"greedy", WideCollapse::greedy}, {"sah", WideCollapse::sah}},
                         "which binary nodes become wide nodes; greedy: open the largest inner "
                         "child until N children; sah: least summed surface area of the wide "
                         "nodes (optimal)");

// Diagonal slabs beside the boxes (a 14-DOP per slot): on the SF 5 sphere flake's primary rays, 22%
// fewer node visits and 39% fewer leaf visits than the boxes alone, 1.14x the speed; on the
// tessellated flake 0.92-0.98x, so the boxes alone stay the default (bvh16 paired against Embree
// medium, `rtlab_bench --suite targets`; docs/results.md, "Structures: speed, memory, build time
// (against Embree)").
const Choice<bool> diagonal_slabs =
    choice<bool>("bounds",
                 "aabb",
                 {{"aabb", false}, {"dop14", true}},
                 "child bounds; aabb: boxes; dop14: boxes and slabs along the four diagonals "
                 "(14-DOPs; plain traversal tests both, robust traversal the boxes)");

/// bvh4, bvh8, bvh16: the source tree collapsed with the spec's order and collapse rule, with
/// diagonal slabs when the spec asks for them.
template <unsigned N>
WideBvh<N> collapse_row(Bvh source, const AccelSpec& s, const BuildInput& in) {
    WideBvh<N> w = collapse_bvh<N>(std::move(source), child_order.of(s), collapse.of(s));
    if (diagonal_slabs.of(s) && !w.nodes.empty()) {
        add_diag_bounds(w, in);
    }
    return w;
}

/// bvh8q: collapse_row<8> with its nodes quantised.
WideBvh<8> quantize_row(Bvh source, const AccelSpec& s, const BuildInput&) {
    return quantize_bvh8(std::move(source), child_order.of(s), collapse.of(s));
}

/// bvh:pair: the source tree converted with the spec's order.
PairBvh pair_row(Bvh source, const AccelSpec& s, const BuildInput&) {
    return PairBvh::convert(std::move(source), child_order.of(s));
}

/// A layout row (bvh:pair, bvh4, bvh8, ...): the `from` builder's tree (spec's Config) converted
/// by Convert(tree, spec, input), the whole row (build, alignment, conversion) on the spec's
/// `threads`.
template <auto Convert>
AnyAccel layout_row(const BuildInput& in, const AccelSpec& s) {
    return with_threads(threads_of(s),
                        [&]() -> AnyAccel { return Convert(aligned_source(in, s), s, in); });
}

// A layout row's source-tree parameters take effect only with the `from` builders that read them,
// the standalone rows' lists: bins with the binned builders, ct, ci and block with every SAH
// builder, morton_bits with LBVH (max_leaf with all).
const std::vector<std::string_view> binned_builders{"pbinned", "binned", "sbvh"};
const std::vector<std::string_view> sah_builders{"pbinned", "binned", "sweep", "sbvh"};
const ParamSpec from_bins = only_with(bins.param, from.param.key, binned_builders);
const ParamSpec from_ct = only_with(sah_ct, from.param.key, sah_builders);
const ParamSpec from_ci = only_with(bvh_ci.param, from.param.key, sah_builders);
const ParamSpec from_morton_bits = only_with(morton_bits.param, from.param.key, {"lbvh"});
// The layouts with SoA leaves (bvh4, bvh8, bvh16, bvh8q, bvh:pair) build source trees that count
// primitives in blocks of 4, the leaves' group (one 4-lane test, half of an 8-lane one): bvh8
// traced the SF 4 mesh 1.04x as fast as with 1, paired with Embree (watertight + robust 0.99-1.01x;
// analytic SF 4 1.00-1.02x); bvh:pair traced within noise (0.98-1.03x) and built its source tree in
// 25-35% less time (`rtlab_bench --suite targets` paired rows; docs/results.md, "Structures: speed,
// memory, build time (against Embree)").
const ParamSpec soa_block =
    only_with(with_default(sah_block.param, 4), from.param.key, sah_builders);
// A quantised node stores leaf counts in 16 bits.
const ParamSpec qwide_max_leaf = with_max(sah_max_leaf, 65535);
// The pair layout's source tree: leaves of up to 16 with ct 8 ran 1.2-1.35x faster than 4 and 1 on
// the tessellated SF 4 (SoA leaves) and 1.03-1.08x on the analytic one; 32 bins, leaves of up to 32
// and ct 16 then ran 1.04-1.075x faster than that over 262,144 rays on the tessellated SF 4 and
// 1.01-1.03x on the analytic SF 4/5 (`rtlab trace --threads 1 --repeat 9`), within 1% over the
// 16,384 of `rtlab_bench --suite targets`, and build 10% faster (fewer nodes; docs/results.md,
// "Structures: speed, memory, build time (against Embree)").
const ParamSpec pair_max_leaf = with_default(max_leaf.param, 32);
const ParamSpec pair_bins = with_default(from_bins, 32);
const ParamSpec pair_ct = with_default(from_ct, 16);

// Rows that take the same parameters: the wide layouts, the kd-trees.
const std::vector<ParamSpec> kd_params{kd_ct.param,     kd_ci.param,        empty_bonus.param,
                                       max_depth.param, min_leaf.param,     perfect.param,
                                       threads,         kd_traversal.param, kd_leaves};
const std::vector<ParamSpec> wide_params{
    from.param,   leaves.param, leaf_align, child_order.param, collapse.param, diagonal_slabs.param,
    sah_max_leaf, from_bins,    from_ct,    from_ci,           soa_block,      from_morton_bits,
    threads};

AnyAccel brute_row(const BuildInput& in, const AccelSpec&) {
    return BruteForce::build(in);
}

// The rows after brute force and the binary builders.
const AccelEntry other_rows[] = {
    {"bvh:pair",
     "binary BVH, both child boxes in the parent (64-byte node), one SSE test, the ray's side "
     "of the split first",
     {from.param, leaves.param, leaf_align, child_order.param, pair_max_leaf, pair_bins, pair_ct,
      from_ci, soa_block, from_morton_bits, threads},
     &layout_row<&pair_row>},
    {"bvh4", "4-wide BVH collapsed from a binary build by surface area, SIMD node test",
     wide_params, &layout_row<&collapse_row<4>>},
    {"bvh8", "8-wide BVH collapsed from a binary build by surface area, SIMD node test",
     wide_params, &layout_row<&collapse_row<8>>},
    {"bvh16",
     "16-wide BVH collapsed from a binary build by surface area, one 16-lane node test (AVX-512; "
     "two 8-lane ones on AVX2)",
     wide_params, &layout_row<&collapse_row<16>>},
    {"bvh8q",
     "bvh8 with each node's child boxes quantised to 8 bits per plane on a per-node grid, rounded "
     "outward (128-byte nodes instead of 256)",
     {from.param, leaves.param, leaf_align, child_order.param, collapse.param, qwide_max_leaf,
      from_bins, from_ct, from_ci, soa_block, from_morton_bits, threads},
     &layout_row<&quantize_row>},
    {"kdtree:sah",
     "kd-tree, O(N log N) SAH event sweep (Wald & Havran 2006), parallel with TBB, deterministic",
     kd_params, &row<build_kdtree_sah, kd_config>},
    {"kdtree:median",
     "kd-tree, spatial median of the longest axis, SAH termination, parallel with TBB", kd_params,
     &row<build_kdtree_median, kd_config>},
    {"grid:uniform",
     "uniform grid, Woo resolution, 3D-DDA (Amanatides & Woo 1987)",
     {density.param, max_res.param, threads},
     &threaded_row<build_grid_uniform, grid_config>},
    {"grid:two_level",
     "two-level grid: coarse top grid, a Woo-sized grid in each non-empty top cell over the part "
     "its primitives cover (Kalojanov et al. 2011), 3D-DDA in both levels, parallel build",
     {top_density.param, leaf_density.param, grid2_max_res.param, threads},
     &threaded_row<build_grid_two_level, grid2_config>},
};

}  // namespace

std::span<const AccelEntry> accel_registry() {
    static const std::vector<AccelEntry> rows = [] {
        std::vector<AccelEntry> r{
            {"brute", "brute force: every primitive box per ray (the reference)", {}, &brute_row}};
        for (const BinaryBuilder& b : binary_builders) {
            r.push_back(b.row);
        }
        r.insert(r.end(), std::begin(other_rows), std::end(other_rows));
        return r;
    }();
    return rows;
}

CostParams cost_params(const AccelSpec& spec) {
    // The BVH and kd-tree rows spell their SAH costs alike.
    CostParams p;
    p.ct = spec.value_or(bvh_ct.param.key, p.ct);
    p.ci = spec.value_or(bvh_ci.param.key, p.ci);
    return p;
}

bool slot_ordered_leaves(const AccelSpec& s) {
    return leaves.of_or(s, true);
}

std::span<const std::string_view> accel_variants() {
    // bvh16 with diagonal slabs: the fastest layout on the analytic sphere flakes.
    static constexpr std::string_view variants[] = {"bvh16,bounds=dop14"};
    return variants;
}

}  // namespace rtlab
