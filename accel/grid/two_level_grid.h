#pragma once
// Two-level grid after Kalojanov, Billeter & Slusallek 2011 ("Two-level grids for ray tracing on
// GPUs"): a coarse top grid (Woo's rule with a low density) whose non-empty cells each hold their
// own uniform grid, sized by Woo's rule from the cell's primitive count and a second density.
// One change from the paper, for scenes such as a teapot in a stadium: a sub-grid spans only the
// part of its top cell its primitives cover (the union of their clipped boxes), not the whole
// cell, so a small dense object in one big top cell still gets small cells. Both levels are walked
// by the same 3D-DDA (accel/grid/dda.h); the mailbox of the ray is shared by both levels. Cells
// and primitive references are compact arrays: one CSR over the cells of all sub-grids.

#include "accel/accel.h"
#include "accel/grid/dda.h"
#include "accel/window_leaf.h"
#include "base/large_pages.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {

/// Build parameters of the two-level grid.
struct TwoLevelGridConfig {
    float top_density = 0.0625f;  ///< lambda_1: top cells per primitive (Woo's rule)
    /// lambda_2: cells per primitive of each sub-grid. 1 beat 2 and 4 on the flake with its floor
    /// and in the stadium, every ray kind, and 0.5 on all but the stadium's diffuse rays
    /// (sweeps/grid-densities.json; docs/results.md, "The two-level grid and the kd-tree").
    float leaf_density = 1.0f;
    std::uint32_t max_res = 256;  ///< upper bound on the resolution of either level per axis
};

/// One sub-grid: its frame (over the part of its top cell its primitives cover) and the index of
/// its first cell in TwoLevelGrid::cell_start.
struct SubGrid {
    GridFrame frame;
    std::uint32_t first_cell = 0;
    friend bool operator==(const SubGrid&, const SubGrid&) = default;
};

/// The two-level grid: the top frame over the union of the primitive boxes; top_sub[i] is the
/// sub-grid of top cell i (no_sub when empty); cell j of sub-grid s holds
/// cell_prims[cell_start[first_cell + j], cell_start[first_cell + j + 1]).
struct TwoLevelGrid : LeafWalkQueries<TwoLevelGrid> {
    using Config = TwoLevelGridConfig;
    static constexpr std::uint32_t no_sub = std::numeric_limits<std::uint32_t>::max();

    GridFrame top;                       ///< the top grid (res all 0 when no primitive)
    std::vector<std::uint32_t> top_sub;  ///< per top cell: index into subs, or no_sub
    std::vector<SubGrid> subs;           ///< the sub-grids, in top-cell order
    // Cells in huge pages once 2 MiB or more (base/large_pages.h), as bvh:pair's nodes.
    LargeVector<std::uint32_t> cell_start;  ///< CSR offsets over all sub-grid cells (+ 1)
    LargeVector<std::uint32_t> cell_prims;  ///< primitive ids, cell by cell, ascending per cell
    std::vector<bool> prim_present;         ///< per primitive id: its box passes is_usable_box

    /// The top grid's box.
    Bounds3f bounds() const { return top.box; }

    /// Top cells plus sub-grid cells as nodes, non-empty sub-grid cells as leaves, depth 1;
    /// sah_cost is the grid's own SAH value: sum over top cells SA(cell)/SA(box) * K_T plus over
    /// sub-grid cells SA(cell)/SA(box) * (K_T + K_I n_cell) with K_T = 1, K_I = 1.5 (as Grid).
    AccelInfo info() const;

    /// Checks: sizes, CSR offsets, sub-grid frames inside their top cells' range of the CSR, ids
    /// in range and every usable primitive referenced.
    std::string validate() const;

    friend bool operator==(const TwoLevelGrid&, const TwoLevelGrid&) = default;

private:
    friend LeafWalkQueries<TwoLevelGrid>;

    /// The walk of intersect and occluded (LeafWalkQueries): top cells front to back, in each its
    /// sub-grid's cells front to back, calling visit(id) for each primitive (once per ray, unless
    /// evicted from the 8-entry mailbox); true from visit stops it. It ends once ray.tmax lies
    /// within the current cell of either level.
    template <bool IsRobust, class S, class Visit>
    bool walk_ids(Rayf& ray, S& stats, Visit& visit) const {
        if (!is_valid(ray) || top_sub.empty()) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        GridMailbox mailbox;
        return dda_walk<IsRobust>(top, ray, sr, stats, [&](std::size_t top_index) {
            const std::uint32_t s = top_sub[top_index];
            if (s == no_sub) {
                return false;
            }
            const SubGrid& sub = subs[s];
            // The sub-grid is walked over the whole ray window: its box lies within its (padded)
            // top cell, and a hit beyond the top cell does not end the top-level walk early.
            return dda_walk<IsRobust>(sub.frame, ray, sr, stats, [&](std::size_t index) {
                const std::size_t c = sub.first_cell + index;
                for (std::uint32_t i = cell_start[c]; i < cell_start[c + 1]; ++i) {
                    const std::uint32_t id = cell_prims[i];
                    if (!mailbox.seen_or_add(id) && visit(id)) {
                        return true;
                    }
                }
                return false;
            });
        });
    }
};

static_assert(Accel<TwoLevelGrid>);

}  // namespace rtlab
