// Two-level grid builder (Kalojanov, Billeter & Slusallek 2011). Top grid by Woo's rule with
// top_density over all primitives; every primitive (in parallel over blocks of ids) is listed in
// the top cells its box overlaps (clipped to each cell when a clip callback is given), keeping the
// part of it inside the cell. Each non-empty top cell gets a sub-grid over the union of those
// parts, resolution by Woo's rule with leaf_density and the cell's reference count; sub-grids are
// built in parallel (TBB, one task per top cell, results concatenated in top-cell order, so the
// structure does not depend on the thread count). Epsilon policy as the uniform grid: boxes are
// widened by 1e-4 cell + 4 ulp of the level's coordinates before they are mapped to cells of that
// level. Cost: O(N + references + cells) work.

#include "accel/grid/cell_map.h"
#include "accel/grid/cell_refs.h"
#include "accel/grid/two_level_grid.h"
#include "base/thread_arena.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

namespace rtlab {

namespace {

/// One primitive listed in one top cell: its id and its part inside the (padded) cell.
struct TopRef {
    std::uint32_t id;
    Bounds3f part;
};

/// The cells of one sub-grid in local CSR form.
struct LocalGrid {
    GridFrame frame;
    std::vector<std::uint32_t> start;  ///< local offsets, size cells + 1
    std::vector<std::uint32_t> prims;
};

/// The sub-grid of one top cell over the parts refs list (ids ascending).
LocalGrid build_sub(std::span<const TopRef> refs,
                    const ClipFn& clip,
                    const TwoLevelGridConfig& cfg) {
    Bounds3f tight;
    for (const TopRef& r : refs) {
        tight.extend(r.part);
    }
    LocalGrid g;
    g.frame =
        GridFrame::over(tight, woo_resolution(tight, refs.size(), cfg.leaf_density, cfg.max_res));
    const CellMapper map(g.frame);
    // (cell, id) references, sorted by cell: ids stay ascending within a cell.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    pairs.reserve(refs.size());
    for (const TopRef& r : refs) {
        map.for_cells(r.part, r.id, clip, [&](std::size_t c, const Bounds3f&) {
            pairs.emplace_back(static_cast<std::uint32_t>(c), r.id);
        });
    }
    refs_to_csr(pairs, g.frame.cell_count(), g.start, g.prims);
    return g;
}

TwoLevelGrid build(const BuildInput& in, const TwoLevelGridConfig& cfg) {
    TwoLevelGrid g;
    g.prim_present.resize(in.bounds.size());
    Bounds3f box;
    std::size_t present = 0;
    for (std::size_t i = 0; i < in.bounds.size(); ++i) {
        if (is_usable_box(in.bounds[i])) {
            g.prim_present[i] = true;
            box.extend(in.bounds[i]);
            ++present;
        }
    }
    if (present == 0) {
        return g;
    }
    g.top = GridFrame::over(box, woo_resolution(box, present, cfg.top_density, cfg.max_res));
    const CellMapper top_map(g.top);

    // Top level: every primitive's parts per top cell (gathered in parallel, in id order), then
    // sorted by cell: ids stay ascending within a cell.
    std::vector<std::uint32_t> top_start;
    std::vector<TopRef> refs;
    refs_to_csr(gather_cell_refs<TopRef>(static_cast<std::uint32_t>(in.bounds.size()),
                                         [&](std::uint32_t id, auto&& emit) {
                                             if (g.prim_present[id]) {
                                                 top_map.for_cells(
                                                     in.bounds[id], id, in.clip,
                                                     [&](std::size_t c, const Bounds3f& part) {
                                                         emit(c, TopRef{id, part});
                                                     });
                                             }
                                         }),
                g.top.cell_count(), top_start, refs);
    const std::size_t top_cells = g.top.cell_count();

    // Sub-grids of the non-empty top cells, in parallel, then concatenated in top-cell order.
    g.top_sub.assign(top_cells, TwoLevelGrid::no_sub);
    std::vector<std::uint32_t> filled;
    for (std::uint32_t c = 0; c < top_cells; ++c) {
        if (top_start[c + 1] > top_start[c]) {
            g.top_sub[c] = static_cast<std::uint32_t>(filled.size());
            filled.push_back(c);
        }
    }
    std::vector<LocalGrid> locals(filled.size());
    tbb::parallel_for(std::size_t{0}, filled.size(), [&](std::size_t s) {
        const std::uint32_t c = filled[s];
        locals[s] = build_sub(
            std::span(refs).subspan(top_start[c], top_start[c + 1] - top_start[c]), in.clip, cfg);
    });
    std::size_t cells = 0, prims = 0;
    for (const LocalGrid& l : locals) {
        cells += l.frame.cell_count();
        prims += l.prims.size();
    }
    g.subs.reserve(locals.size());
    g.cell_start.reserve(cells + 1);
    g.cell_prims.reserve(prims);
    for (const LocalGrid& l : locals) {
        g.subs.push_back({l.frame, static_cast<std::uint32_t>(g.cell_start.size())});
        const auto offset = static_cast<std::uint32_t>(g.cell_prims.size());
        for (std::size_t k = 0; k + 1 < l.start.size(); ++k) {
            g.cell_start.push_back(offset + l.start[k]);
        }
        g.cell_prims.insert(g.cell_prims.end(), l.prims.begin(), l.prims.end());
    }
    g.cell_start.push_back(static_cast<std::uint32_t>(g.cell_prims.size()));
    return g;
}

}  // namespace

TwoLevelGrid build_grid_two_level(const BuildInput& in,
                                  const TwoLevelGridConfig& cfg,
                                  std::uint32_t threads) {
    return with_threads(threads, [&] { return build(in, cfg); });
}

AccelInfo TwoLevelGrid::info() const {
    AccelInfo i;
    i.nodes = top_sub.size() + (cell_start.empty() ? 0 : cell_start.size() - 1);
    i.max_depth = top_sub.empty() ? 0 : 1;
    i.bytes = (top_sub.size() + cell_start.size() + cell_prims.size()) * sizeof(std::uint32_t) +
              subs.size() * sizeof(SubGrid);
    const double box_area = static_cast<double>(top.box.surface_area());
    const auto area_ratio = [&](const Vec3f& size) {
        return box_area > 0 ? static_cast<double>(Bounds3f(Vec3f{}, size).surface_area()) / box_area
                            : 1.0;
    };
    i.sah_cost = static_cast<double>(top_sub.size()) * area_ratio(top.cell_size);
    for (const SubGrid& s : subs) {
        add_cell_costs(i, cell_start, s.first_cell, s.frame.cell_count(),
                       area_ratio(s.frame.cell_size));
    }
    set_per_prim_figures(i, cell_prims.size(), prim_present);
    return i;
}

std::string TwoLevelGrid::validate() const {
    if (present_count(prim_present) == 0) {
        return top_sub.empty() && subs.empty() && cell_start.empty() && cell_prims.empty()
                   ? std::string{}
                   : "cells although no primitive exists";
    }
    if (top.res[0] == 0 || top.res[1] == 0 || top.res[2] == 0 ||
        top_sub.size() != top.cell_count()) {
        return "top grid resolution does not match its cells";
    }
    std::size_t expected_first = 0, next_sub = 0;
    for (std::size_t c = 0; c < top_sub.size(); ++c) {
        if (top_sub[c] == no_sub) {
            continue;
        }
        if (top_sub[c] != next_sub || top_sub[c] >= subs.size()) {
            return "top cell " + std::to_string(c) + " names sub-grid out of order";
        }
        const SubGrid& s = subs[next_sub++];
        if (s.first_cell != expected_first || s.frame.cell_count() == 0) {
            return "sub-grid " + std::to_string(next_sub - 1) + " cells do not follow the previous";
        }
        expected_first += s.frame.cell_count();
        for (std::size_t a = 0; a < 3; ++a) {
            if (!(s.frame.box.lo[a] >= top.box.lo[a] && s.frame.box.hi[a] <= top.box.hi[a] &&
                  s.frame.box.lo[a] <= s.frame.box.hi[a])) {
                return "sub-grid " + std::to_string(next_sub - 1) + " box leaves the top box";
            }
        }
    }
    if (next_sub != subs.size() || cell_start.size() != expected_first + 1) {
        return "CSR offsets do not match the sub-grid cells";
    }
    return check_csr_cells(cell_start, cell_prims, prim_present);
}

}  // namespace rtlab
