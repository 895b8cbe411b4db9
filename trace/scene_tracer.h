#pragma once
// Traces batches of rays through a scene: one acceleration structure per non-empty primitive set
// (a scene of spheres never runs triangle code), the closest hit over all sets, in parallel with
// TBB. Each ray is independent, so results do not depend on the thread count.

#include "accel/accel.h"
#include "accel/any_accel.h"
#include "accel/cost_model.h"
#include "intersect/hit.h"
#include "scene/scene.h"
#include "trace/exact_query.h"
#include "trace/prim_sets.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rtlab {

/// How to trace: which structure, which intersection methods, robust traversal or not.
struct TraceSetup {
    /// The structure, parsed once from NAME[,key=value]... (accel/spec.h).
    AccelSpec accel = parse_accel_spec(default_accel);
    /// Method names (one per family at most); families not named use their default, the first
    /// of their list (method_families()).
    std::vector<std::string> methods;
    bool robust = false;  ///< conservative box tests in traversal (Ize 2013)
    /// Certified triangle hits (trace/exact_query.h): robust traversal, the exact test, exact ties
    /// to the lowest id. For scenes of triangles only, with no method named.
    bool exact = false;
};

/// A scene prepared for tracing. Build once, trace many batches.
class SceneTracer {
public:
    /// Prepares every non-empty primitive set and builds its structure. Throws
    /// std::invalid_argument for an unknown structure or method name.
    SceneTracer(const Scene& scene, const TraceSetup& setup);

    /// Closest hit for every ray (hits[i] for rays[i]; a miss keeps prim == invalid_id and
    /// t = +inf). Throws std::invalid_argument when a set's method cannot report hit points
    /// (segura_feito). Adds counts to *stats when given (a separate, slower code path). In exact
    /// mode, the certified closest hits.
    void intersect(std::span<const Rayf> rays,
                   std::span<Hit> hits,
                   TraversalStats* stats = nullptr) const;

    /// Closest hit for every ray as intersect(), also adding each ray's own traversal counts to
    /// per_ray[i] (nodes and primitive tests over all sets; rays = 1 per set traversed). For
    /// per-pixel heat maps; slower than intersect(). Not in exact mode.
    void intersect_counted(std::span<const Rayf> rays,
                           std::span<Hit> hits,
                           std::span<TraversalStats> per_ray) const;

    /// The traversal alone of intersect(): every set's structure walked for ray i with its window
    /// ending at hits[i].t (the closest hit intersect() found), leaves offered but not tested; a
    /// trace's time less this one is about its leaf work (`rtlab trace --leaf-time`).
    void traverse(std::span<const Rayf> rays, std::span<const Hit> hits) const;

    /// Any hit for every ray: blocker[i] is the global id of a primitive that blocks rays[i]'s
    /// window (whichever traversal met first), or invalid_id when nothing does.
    void occluded(std::span<const Rayf> rays,
                  std::span<std::uint32_t> blocker,
                  TraversalStats* stats = nullptr) const;

    /// How often exact mode needed exact arithmetic on rays (closest hits, or any hits with
    /// any_hit): one more pass. Throws std::logic_error outside exact mode.
    ExactCounts exact_counts(std::span<const Rayf> rays, bool any_hit) const;
    /// True in exact mode (TraceSetup::exact).
    bool exact() const { return exact_; }

    /// The structure every set was built with; accel_spec().canonical() names all parameters.
    const AccelSpec& accel_spec() const { return accel_spec_; }
    /// Wall time of building all structures (not of preparing primitives), in milliseconds.
    double build_ms() const { return build_ms_; }
    /// "family=method" for every set, in set order, e.g. {"triangle=watertight"}.
    const std::vector<std::string>& set_methods() const { return set_methods_; }
    /// Info of every set's structure (set order as set_methods()).
    std::vector<AccelInfo> infos() const;
    /// Bytes of the primitive data traversal reads beside the structures, over all sets: a set's
    /// slot-ordered leaf data (trace/leaf_kernel.h; padding slots included) when it has them, else
    /// its prepared primitives with the global id map; in exact mode, the triangles and ids the
    /// certified test reads.
    std::size_t leaf_bytes() const;
    /// The one cost model's expected counts (accel/cost_model.h) of every set's structure, and
    /// with_epo the end-point overlap of a BVH over the triangle set (-1 for other sets and
    /// structures; slow: clips triangles against every node), set order as set_methods().
    std::vector<std::pair<CostEstimate, double>> cost_figures(const CostParams& p,
                                                              bool with_epo) const;
    /// Number of global primitives.
    std::uint32_t primitive_count() const { return prim_count_; }
    /// The prepared sets, in set order (tests check which leaf path a set takes).
    const std::vector<AnyPrimSet>& sets() const { return sets_; }

private:
    std::vector<AnyPrimSet> sets_;
    std::vector<std::string> set_methods_;
    AccelSpec accel_spec_;
    double build_ms_ = 0;
    bool robust_ = false;
    bool exact_ = false;
    std::uint32_t prim_count_ = 0;
    std::vector<Trianglef> triangles_;  ///< the triangle set's shapes, local order (EPO, exact)
    /// Exact mode with slot-ordered leaves: the triangles and global ids in leaf-slot order.
    std::pair<std::vector<Trianglef>, std::vector<std::uint32_t>> exact_slots_;

    /// Checks that exact mode can serve the scene and set-up, then switches to it.
    void enter_exact(const TraceSetup& setup);
    /// The exact query's triangles and the triangle set's structure (exact mode, one set).
    std::pair<ExactTriangles, const AnyAccel*> exact_set() const;
};

}  // namespace rtlab
