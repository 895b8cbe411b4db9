#pragma once
// Uniform grid: cells in CSR form (cell_start / cell_prims), resolution by Woo's rule
// (res_i = d_i * cbrt(lambda N / V)); traversed by the 3D-DDA of Amanatides & Woo 1987, "A fast
// voxel traversal algorithm for ray tracing", with a small per-ray mailbox against re-testing
// primitives that span several cells. Cost per ray: one step per cell pierced plus the cells'
// primitives; the walk ends at the first cell whose exit lies beyond the closest hit.

#include "accel/accel.h"
#include "accel/grid/dda.h"
#include "accel/window_leaf.h"
#include "base/large_pages.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {

/// Build parameters of the uniform grid.
struct GridConfig {
    float density = 4.0f;         ///< lambda: target cells per primitive (Woo's formula)
    std::uint32_t max_res = 512;  ///< upper bound on the resolution along each axis
};

/// A uniform grid over the union of the primitive boxes (its GridFrame); cell i holds
/// cell_prims[cell_start[i], cell_start[i + 1]).
struct Grid : GridFrame, LeafWalkQueries<Grid> {
    using Config = GridConfig;

    // Cells in huge pages once 2 MiB or more (base/large_pages.h), as bvh:pair's nodes.
    LargeVector<std::uint32_t> cell_start;  ///< CSR offsets, size cells + 1
    LargeVector<std::uint32_t> cell_prims;  ///< primitive ids, cell by cell, ascending per cell
    std::vector<bool> prim_present;         ///< per primitive id: its box passes is_usable_box

    /// The grid's box.
    Bounds3f bounds() const { return box; }

    /// Cells as nodes, non-empty cells as leaves; sah_cost is the SAH value of the cells seen as
    /// leaves, sum over cells (SA(cell) / SA(box)) * (1 + 1.5 n_cell) (K_T = 1, K_I = 1.5).
    AccelInfo info() const;

    /// Checks: CSR offsets monotone and complete, ids in range, every primitive with a non-empty
    /// box in at least one cell, resolution at least 1 per axis when primitives exist.
    std::string validate() const;

    friend bool operator==(const Grid&, const Grid&) = default;

private:
    friend LeafWalkQueries<Grid>;

    /// The 3D-DDA (dda_walk) for intersect and occluded (LeafWalkQueries). visit(id) is called
    /// for every primitive of each cell pierced (front to back; once per ray, unless evicted from
    /// the 8-entry mailbox) and returns true to stop.
    template <bool IsRobust, class S, class Visit>
    bool walk_ids(Rayf& ray, S& stats, Visit& visit) const {
        if (!is_valid(ray) || cell_start.empty()) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        GridMailbox mailbox;
        return dda_walk<IsRobust>(*this, ray, sr, stats, [&](std::size_t index) {
            for (std::uint32_t i = cell_start[index]; i < cell_start[index + 1]; ++i) {
                const std::uint32_t id = cell_prims[i];
                if (!mailbox.seen_or_add(id) && visit(id)) {
                    return true;
                }
            }
            return false;
        });
    }
};

static_assert(Accel<Grid>);

}  // namespace rtlab
