#pragma once
// The 3D-DDA of Amanatides & Woo 1987 ("A fast voxel traversal algorithm for ray tracing") over
// one regular grid of cells, shared by the uniform grid and both levels of the two-level grid.
// A grid frame is its box, cell size (with reciprocal) and resolution; a cell's linear index is
// x + res[0] * (y + res[1] * z). Axes of zero extent have one cell and inverse cell size 0.

#include "accel/accel.h"
#include "intersect/box/slabs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rtlab {

/// The geometry of one regular grid of cells.
struct GridFrame {
    std::array<std::uint32_t, 3> res{0, 0, 0};  ///< cells per axis
    Bounds3f box;                               ///< the grid's box
    Vec3f cell_size;                            ///< box extent / res per axis
    Vec3f inv_cell_size;                        ///< 1 / cell_size (0 on an axis of zero extent)

    /// Number of cells.
    std::size_t cell_count() const { return static_cast<std::size_t>(res[0]) * res[1] * res[2]; }

    /// Linear index of cell (x, y, z).
    std::size_t index(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return x + res[0] * (static_cast<std::size_t>(y) + res[1] * static_cast<std::size_t>(z));
    }

    /// The frame over `b` with `r` cells per axis.
    static GridFrame over(const Bounds3f& b, const std::array<std::uint32_t, 3>& r) {
        GridFrame f;
        f.res = r;
        f.box = b;
        const Vec3f d = b.diagonal();
        for (std::size_t a = 0; a < 3; ++a) {
            f.cell_size[a] = d[a] / static_cast<float>(r[a]);
            f.inv_cell_size[a] = d[a] > 0.0f ? 1.0f / f.cell_size[a] : 0.0f;
        }
        return f;
    }

    friend bool operator==(const GridFrame&, const GridFrame&) = default;
};

/// Cells per axis by Woo's rule (Graphics Gems IV, 1992; Cleary & Wyvill 1988): res_i = d_i *
/// cbrt(density * n / V), over the axes of non-zero extent (the others get one cell), clamped to
/// [1, max_res].
std::array<std::uint32_t, 3> woo_resolution(const Bounds3f& box,
                                            std::size_t n,
                                            double density,
                                            std::uint32_t max_res);

/// True when the robust walk's rounding stays within the builders' padding for this ray: on every
/// axis with more than one cell, 2^-50 (|org| + the grid's largest |coordinate|) <= 1e-4 cell / 2
/// (cell_map.h pads by 1e-4 cell). It fails only for origins some 10^10 cells away.
inline bool dda_robust_bound_holds(const GridFrame& g, const Rayf& ray) {
    for (std::size_t a = 0; a < 3; ++a) {
        const double mag = std::max(std::abs(static_cast<double>(g.box.lo[a])),
                                    std::abs(static_cast<double>(g.box.hi[a])));
        if (g.res[a] > 1 && 0x1.0p-50 * (mag + std::abs(static_cast<double>(ray.org[a]))) >
                                0.5e-4 * static_cast<double>(g.cell_size[a])) {
            return false;
        }
    }
    return true;
}

/// The robust 3D-DDA over the clipped window [t0, t1] (t0 no later than the exact ray's entry,
/// t1 no earlier than its exit: the outward-widened clip). Conservative, and why:
/// - It runs in double. A cell's region is [lo + k s, lo + (k + 1) s] on each axis (lo, s the
///   frame's floats), the first and last cells extended to infinity as the builders' clamp does.
///   Plane positions and the entry point's coordinates are then exact up to 2^-53 relative, and
///   a crossing time (x - org) * (1 / dir) is off by at most 4 u (|x| + |org|) / |dir| (u = 2^-53).
/// - Per axis, the cell the walk holds at parameter tau is the exact point p(tau)'s cell, or its
///   neighbour across a plane that p(tau) is within 2^-50 (|org| + |x|) of: each axis's index
///   changes only at that axis's own (rounded) crossing times. The walk visits the cell it holds
///   for every tau in [t0, t1]: it never stops at the grid's side (an index that would leave the
///   grid stays in its last cell and that axis stops stepping), only past t1, or once the hit
///   found lies within the cell just visited.
/// - Builders list a primitive in every cell whose region is within 1e-4 cell of its box on each
///   axis (cell_map.h; the 4-ulp term of the padding absorbs the float cell boxes the clipping
///   builders use). So when dda_robust_bound_holds, every primitive the exact ray meets, at p(tau)
///   inside its box, is listed in a cell the walk visits. When the bound fails, every cell is
///   visited. The error model is the standard one of Higham, "Accuracy and Stability of Numerical
///   Algorithms" (2002), ch. 3.
template <class S, class CellFn>
bool dda_walk_robust(
    const GridFrame& g, const Rayf& ray, float t0f, float t1f, S& stats, CellFn&& cell_fn) {
    if (!dda_robust_bound_holds(g, ray)) {
        for (std::size_t c = 0; c < g.cell_count(); ++c) {
            stats.count_node();
            if (cell_fn(c)) {
                return true;
            }
        }
        return false;
    }
    const double t0 = t0f, t1 = t1f;
    std::array<int, 3> cell{}, step{};
    std::array<double, 3> t_next{}, org{}, inv_dir{};
    const auto last = [&](std::size_t a) { return static_cast<int>(g.res[a]) - 1; };
    // Where the ray leaves its cell along axis a (+inf at the grid's side or when it never does).
    const auto next_crossing = [&](std::size_t a) {
        if (step[a] == 0 || cell[a] == (step[a] > 0 ? last(a) : 0)) {
            return std::numeric_limits<double>::infinity();
        }
        const int plane = step[a] > 0 ? cell[a] + 1 : cell[a];
        const double x = static_cast<double>(g.box.lo[a]) +
                         static_cast<double>(plane) * static_cast<double>(g.cell_size[a]);
        return (x - org[a]) * inv_dir[a];
    };
    for (std::size_t a = 0; a < 3; ++a) {
        org[a] = ray.org[a];
        const double d = ray.dir[a];
        step[a] = d > 0 ? 1 : (d < 0 ? -1 : 0);
        inv_dir[a] = step[a] != 0 ? 1.0 / d : 0.0;
        if (g.res[a] > 1) {
            const double e = org[a] + t0 * d;  // t0 * d is exact in double
            const double c = std::floor((e - static_cast<double>(g.box.lo[a])) /
                                        static_cast<double>(g.cell_size[a]));
            cell[a] =
                c > static_cast<double>(last(a)) ? last(a) : (c > 0.0 ? static_cast<int>(c) : 0);
        }
        t_next[a] = next_crossing(a);
    }
    for (;;) {
        stats.count_node();
        const std::size_t axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                                       : (t_next[1] < t_next[2] ? 1 : 2);
        const double t_exit = t_next[axis] < t1 ? t_next[axis] : t1;
        if (cell_fn(g.index(static_cast<std::uint32_t>(cell[0]),
                            static_cast<std::uint32_t>(cell[1]),
                            static_cast<std::uint32_t>(cell[2])))) {
            return true;
        }
        // A hit inside this cell cannot be beaten by a later cell; also stop past the window.
        if (static_cast<double>(ray.tmax) <= t_exit || t_exit >= t1) {
            return false;
        }
        cell[axis] += step[axis];
        t_next[axis] = next_crossing(axis);
    }
}

/// Walks the cells of frame g that ray pierces within its window [ray.tmin, ray.tmax] front to
/// back, calling cell_fn(linear index) (counted as a node) for each; cell_fn returns true to stop
/// the walk, and then the walk returns true. The walk ends after a cell once ray.tmax (which
/// cell_fn may shrink) lies within that cell, or at the window's or grid's end, returning false.
/// IsRobust clips outward (Ize 2013) and walks by dda_walk_robust; the plain walk runs in float.
template <bool IsRobust, class S, class CellFn>
bool dda_walk(
    const GridFrame& g, const Rayf& ray, const SlabRay<float>& sr, S& stats, CellFn&& cell_fn) {
    float t0 = ray.tmin, t1 = ray.tmax;
    if (!clip_slabs<IsRobust>(g.box.lo, g.box.hi, sr, t0, t1)) {
        return false;
    }
    if constexpr (IsRobust) {
        return dda_walk_robust(g, ray, t0, t1, stats, cell_fn);
    }
    // The t where the ray leaves cell c along axis a (+inf when it never does).
    const auto next_crossing = [&](std::size_t a, int c, int s) {
        if (s == 0) {
            return std::numeric_limits<float>::infinity();
        }
        const int plane = s > 0 ? c + 1 : c;
        const float x = g.box.lo[a] + static_cast<float>(plane) * g.cell_size[a];
        return (x - sr.org[a]) * sr.inv_dir[a];
    };
    // Entry cell from the entry point; t_next[a] is where the ray leaves it along axis a.
    const Vec3f entry = ray.at(t0);
    std::array<int, 3> cell{}, step{}, out{};
    std::array<float, 3> t_next{};
    for (std::size_t a = 0; a < 3; ++a) {
        const int last = static_cast<int>(g.res[a]) - 1;
        const float c = std::floor((entry[a] - g.box.lo[a]) * g.inv_cell_size[a]);
        cell[a] = c > static_cast<float>(last) ? last : (c > 0.0f ? static_cast<int>(c) : 0);
        if (ray.dir[a] > 0.0f) {
            step[a] = 1;
            out[a] = last + 1;
        } else if (ray.dir[a] < 0.0f) {
            step[a] = -1;
            out[a] = -1;
        }
        t_next[a] = next_crossing(a, cell[a], step[a]);
    }
    for (;;) {
        stats.count_node();
        const std::size_t axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                                       : (t_next[1] < t_next[2] ? 1 : 2);
        const float t_exit = t_next[axis] < t1 ? t_next[axis] : t1;
        if (cell_fn(g.index(static_cast<std::uint32_t>(cell[0]),
                            static_cast<std::uint32_t>(cell[1]),
                            static_cast<std::uint32_t>(cell[2])))) {
            return true;
        }
        // A hit inside this cell cannot be beaten by a later cell; also stop at the window.
        if (ray.tmax <= t_exit || t_exit >= t1 || t_next[axis] > ray.tmax) {
            return false;
        }
        cell[axis] += step[axis];
        if (cell[axis] == out[axis]) {
            return false;
        }
        t_next[axis] = next_crossing(axis, cell[axis], step[axis]);
    }
}

/// Recently tested primitive ids of one ray (lives on the stack: thread-safe), so a primitive
/// spanning several cells is usually tested once.
struct GridMailbox {
    std::array<std::uint32_t, 8> ids;
    std::uint32_t next = 0;
    GridMailbox() { ids.fill(std::numeric_limits<std::uint32_t>::max()); }
    /// True when id was seen; otherwise records it (evicting the oldest).
    bool seen_or_add(std::uint32_t id) {
        for (const std::uint32_t m : ids) {
            if (m == id) {
                return true;
            }
        }
        ids[next] = id;
        next = (next + 1) % ids.size();
        return false;
    }
};

}  // namespace rtlab
