#pragma once
// Which cells of a grid level a primitive's box overlaps, shared by the uniform and the two-level
// grid builders. Epsilon policy: boxes are widened by 1e-4 cell + 4 ulp of the level's
// coordinates before they are mapped to cells, so a primitive touching a cell face is also listed
// in the neighbour that the DDA's rounded entry point or crossing times may select.

#include "accel/accel.h"
#include "accel/grid/dda.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rtlab {

/// Per-axis widening of boxes before they are mapped to the cells of frame f.
inline Vec3f cell_padding(const GridFrame& f) {
    Vec3f pad;
    for (std::size_t a = 0; a < 3; ++a) {
        const float mag = std::max(std::abs(f.box.lo[a]), std::abs(f.box.hi[a]));
        pad[a] = 1e-4f * f.cell_size[a] + 4.0f * std::numeric_limits<float>::epsilon() * mag;
    }
    return pad;
}

/// Cells of one frame overlapped by boxes, padded as the epsilon policy says.
struct CellMapper {
    const GridFrame& f;
    Vec3f pad;
    std::size_t clip_min_cells = 4;  ///< boxes over at most this many cells are not clipped

    explicit CellMapper(const GridFrame& frame) : f(frame), pad(cell_padding(frame)) {}

    /// The cell of coordinate x along axis a, computed in double (so only the padding's 1e-4 cell,
    /// not this rounding, sets how near a box a listed cell lies: dda_walk_robust relies on it).
    std::uint32_t cell_of(double x, std::size_t a) const {
        if (f.res[a] <= 1) {
            return 0;
        }
        const double c = std::floor((x - static_cast<double>(f.box.lo[a])) /
                                    static_cast<double>(f.cell_size[a]));
        return static_cast<std::uint32_t>(std::clamp(c, 0.0, static_cast<double>(f.res[a] - 1)));
    }
    /// The cells [lo, hi] (inclusive, per axis) box b overlaps once widened by pad.
    void cell_range(const Bounds3f& b,
                    std::array<std::uint32_t, 3>& lo,
                    std::array<std::uint32_t, 3>& hi) const {
        for (std::size_t a = 0; a < 3; ++a) {
            lo[a] = cell_of(static_cast<double>(b.lo[a]) - static_cast<double>(pad[a]), a);
            hi[a] = cell_of(static_cast<double>(b.hi[a]) + static_cast<double>(pad[a]), a);
        }
    }
    /// Cell (x, y, z)'s box widened by pad.
    Bounds3f cell_box(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        const std::array<std::uint32_t, 3> c{x, y, z};
        Bounds3f b;
        for (std::size_t a = 0; a < 3; ++a) {
            b.lo[a] = f.box.lo[a] + static_cast<float>(c[a]) * f.cell_size[a] - pad[a];
            b.hi[a] = f.box.lo[a] + static_cast<float>(c[a] + 1) * f.cell_size[a] + pad[a];
        }
        return b;
    }
    /// Calls fn(cell index, part) for every cell box b overlaps, part being primitive id's part
    /// inside the padded cell (clipped when clip is set and finds one, else the box overlap).
    template <class Fn>
    void for_cells(const Bounds3f& b, std::uint32_t id, const ClipFn& clip, Fn&& fn) const {
        std::array<std::uint32_t, 3> lo{}, hi{};
        cell_range(b, lo, hi);
        // Few cells: listing the box's cells costs less than clipping (the clip pays off for
        // large primitives across many cells; within one cell it could only confirm it).
        std::size_t span = 1;
        for (std::size_t a = 0; a < 3; ++a) {
            span *= hi[a] - lo[a] + 1;
        }
        for (int pass = clip && span > clip_min_cells ? 0 : 1; pass < 2; ++pass) {
            std::size_t count = 0;
            for (std::uint32_t z = lo[2]; z <= hi[2]; ++z) {
                for (std::uint32_t y = lo[1]; y <= hi[1]; ++y) {
                    for (std::uint32_t x = lo[0]; x <= hi[0]; ++x) {
                        const Bounds3f cell = cell_box(x, y, z);
                        Bounds3f part = intersect(b, pass == 0 ? clip(id, cell) : cell);
                        if (!is_usable_box(part)) {
                            if (pass == 0) {
                                continue;
                            }
                            part = b;  // rounding emptied the overlap: keep the whole box
                        }
                        fn(f.index(x, y, z), part);
                        ++count;
                    }
                }
            }
            if (count > 0) {
                return;  // the clipped overlap found cells; the box overlap is the fallback
            }
        }
    }

    static Bounds3f intersect(const Bounds3f& a, const Bounds3f& b) {
        Bounds3f r;
        for (std::size_t k = 0; k < 3; ++k) {
            r.lo[k] = std::max(a.lo[k], b.lo[k]);
            r.hi[k] = std::min(a.hi[k], b.hi[k]);
        }
        return r;
    }
};

}  // namespace rtlab
