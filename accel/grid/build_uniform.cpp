// Uniform grid builder. Resolution after Woo (Graphics Gems IV, "Ray tracing polygons using
// spatial subdivision", 1992 / Cleary & Wyvill 1988): res_i = d_i * cbrt(lambda N / V), clamped
// to [1, max_res]; axes of zero extent get one cell and the rule runs over the others. Two passes
// (count, then fill) give the CSR arrays. Boxes are padded before they are mapped to cells as
// accel/grid/cell_map.h says. Cost: O(N + references + cells); the references (and their
// clipping, the expensive part) are gathered in parallel with TBB, deterministically.

#include "accel/grid/cell_map.h"
#include "accel/grid/cell_refs.h"
#include "accel/grid/grid.h"
#include "base/thread_arena.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rtlab {

namespace {

Grid build(const BuildInput& in, const GridConfig& cfg) {
    Grid g;
    g.prim_present.resize(in.bounds.size());
    std::size_t present = 0;
    for (std::size_t i = 0; i < in.bounds.size(); ++i) {
        if (is_usable_box(in.bounds[i])) {
            g.prim_present[i] = true;
            g.box.extend(in.bounds[i]);
            ++present;
        }
    }
    if (present == 0) {
        return g;
    }
    static_cast<GridFrame&>(g) =
        GridFrame::over(g.box, woo_resolution(g.box, present, cfg.density, cfg.max_res));
    const CellMapper map(g);

    // Calls fn(cell index) for every cell primitive id overlaps (its clipped part, when
    // use_clip); returns the number of cells.
    const auto overlap = [&](std::uint32_t id, bool use_clip, auto&& fn) {
        std::size_t count = 0;
        const Bounds3f& b = in.bounds[id];
        std::array<std::uint32_t, 3> lo{}, hi{};
        map.cell_range(b, lo, hi);
        for (std::uint32_t z = lo[2]; z <= hi[2]; ++z) {
            for (std::uint32_t y = lo[1]; y <= hi[1]; ++y) {
                for (std::uint32_t x = lo[0]; x <= hi[0]; ++x) {
                    if (use_clip && !is_usable_box(in.clip(id, map.cell_box(x, y, z)))) {
                        continue;
                    }
                    fn(g.index(x, y, z));
                    ++count;
                }
            }
        }
        return count;
    };
    // The clipped overlap, or the box overlap when there is no clip or it lost the primitive.
    // A box within one cell skips the clip: it could only confirm that cell or lose it to
    // rounding and fall back to it.
    const auto one_cell = [&](std::uint32_t id) {
        std::array<std::uint32_t, 3> lo{}, hi{};
        map.cell_range(in.bounds[id], lo, hi);
        return lo == hi;
    };
    const auto for_cells = [&](std::uint32_t id, auto&& fn) {
        if (!in.clip || one_cell(id) || overlap(id, true, fn) == 0) {
            overlap(id, false, fn);
        }
    };

    // References gathered in parallel (in id order), then sorted by cell: ids stay ascending.
    const auto refs = gather_cell_refs<std::uint32_t>(
        static_cast<std::uint32_t>(in.bounds.size()), [&](std::uint32_t id, auto&& emit) {
            if (g.prim_present[id]) {
                for_cells(id, [&](std::size_t c) { emit(c, id); });
            }
        });
    refs_to_csr(refs, g.cell_count(), g.cell_start, g.cell_prims);
    return g;
}

}  // namespace

/// The uniform grid on `threads` TBB threads (0: all allowed); the grid does not depend on it.
Grid build_grid_uniform(const BuildInput& in, const GridConfig& cfg, std::uint32_t threads) {
    return with_threads(threads, [&] { return build(in, cfg); });
}

AccelInfo Grid::info() const {
    AccelInfo i;
    const std::size_t cells = cell_count();
    i.nodes = cells;
    i.bytes = (cell_start.size() + cell_prims.size()) * sizeof(std::uint32_t);
    const double box_area = static_cast<double>(box.surface_area());
    const Bounds3f one_cell(box.lo, box.lo + cell_size);
    const double p = box_area > 0 ? static_cast<double>(one_cell.surface_area()) / box_area : 1.0;
    add_cell_costs(i, cell_start, 0, cells, p);
    set_per_prim_figures(i, cell_prims.size(), prim_present);
    return i;
}

std::string Grid::validate() const {
    if (present_count(prim_present) == 0) {
        return cell_start.empty() && cell_prims.empty() ? std::string{}
                                                        : "cells although no primitive exists";
    }
    if (res[0] == 0 || res[1] == 0 || res[2] == 0) {
        return "zero resolution with primitives present";
    }
    if (cell_start.size() != cell_count() + 1) {
        return "CSR offsets do not match the cell count";
    }
    return check_csr_cells(cell_start, cell_prims, prim_present);
}

}  // namespace rtlab
