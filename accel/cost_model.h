#pragma once
// One cost model for every structure (docs/architecture.md, "One cost model"): the expected
// number of node visits and primitive tests of a ray that meets the structure's root box, under
// surface-area probabilities (Goldsmith & Salmon 1987; MacDonald & Booth 1990): a random line
// that meets a convex box B meets a convex C inside B with probability SA(C) / SA(B). Each
// structure counts exactly what its traversal counts with TraversalStats:
//   binary BVH (Bvh, PairBvh): every box test is a node: 1 (root) + 2 sum_inner P(inner);
//     primitives sum_leaf P(leaf) n_leaf;
//   wide BVH (bvh4, bvh8): one node per wide node entered: 1 + sum_{inner, not root} P(its box);
//     primitives as above over the leaf slots;
//   kd-tree: every node whose cell the line meets: sum_nodes P(cell); primitives over leaf cells;
//   grids (both levels): every cell the line meets: sum_cells P(cell) (= 1 + sum over axes of
//     (res_a - 1) A_a / (A_x + A_y + A_z), A_a the box's face area across axis a: the exact
//     expected number of cells a random line crosses); primitives with a perfect mailbox (each
//     tested once when the line meets one of its cells): sum_prims P(box spanned by its cells);
//     the 8-entry mailbox retests when cells hold many primitives, so this is a lower bound;
//   brute force: every primitive box is a node; primitives sum_i P(box_i).
// The model ignores early termination (closest hit stops once a hit lies in the current node),
// so it bounds the measured counts of misses and overestimates those of hits. The cost is
// ct * nodes + ci * prims; measured_cost is the same sum over the counted nodes/ray, prims/ray.

#include "accel/any_accel.h"
#include "intersect/triangle/triangle.h"

#include <span>
#include <vector>

namespace rtlab {

/// The two constants of the model.
struct CostParams {
    double ct = 1.0;  ///< cost of one node visit (box test, kd step, grid cell)
    double ci = 1.0;  ///< cost of one primitive test
};

/// ct and ci of a spec: the row's `ct`/`ci` parameters where they take effect, else the defaults.
CostParams cost_params(const AccelSpec& spec);

/// Expected counts per ray meeting the root box.
struct CostEstimate {
    double nodes = 0;  ///< expected node visits (as TraversalStats counts them)
    double prims = 0;  ///< expected primitive tests
    /// ct * nodes + ci * prims.
    double cost(const CostParams& p) const { return p.ct * nodes + p.ci * prims; }
};

// The structures that are no BVH give their own model; every BVH layout is flattened
// (accel/flat_bvh.h) and modelled once.
CostEstimate expected_cost(const BruteForce& a);
CostEstimate expected_cost(const KdTree& a);
CostEstimate expected_cost(const Grid& a);
CostEstimate expected_cost(const TwoLevelGrid& a);

/// The model for whichever structure a holds.
CostEstimate expected_cost(const AnyAccel& a);

/// ct * nodes_per_ray + ci * prims_per_ray: the measured counterpart of CostEstimate::cost.
inline double measured_cost(const CostParams& p, double nodes_per_ray, double prims_per_ray) {
    return p.ct * nodes_per_ray + p.ci * prims_per_ray;
}

/// End-point overlap (Aila, Karras & Laine 2013, "On quality metrics of bounding volume
/// hierarchies"): sum over nodes n of C_n * A((S \ Q(n)) intersected with box(n)) / A(S), S the
/// scene's surface, Q(n) the triangles under n, C_n = ct for inner nodes and ci * n for leaves:
/// the expected cost of nodes a ray ending on the surface enters without needing them. For the
/// BVH layouts (binary, pair, wide; other structures: -1), triangles[id] being primitive id.
/// O(nodes * overlapping leaves); parallel over nodes with TBB.
double end_point_overlap(const AnyAccel& a,
                         std::span<const Trianglef> triangles,
                         const CostParams& p);

/// True when end_point_overlap applies to the structure a holds (a BVH layout).
bool has_end_point_overlap(const AnyAccel& a);

/// The box of every node of the BVH layout a holds (binary, pair, wide: each child slot's box as
/// traversal tests it, quantised ones decoded), root first; empty for other structures.
std::vector<Bounds3f> bvh_node_boxes(const AnyAccel& a);

}  // namespace rtlab
