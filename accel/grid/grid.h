#pragma once
// Uniform grid: cells in CSR form (cell_start / cell_prims), resolution by Woo's rule
// (res_i = d_i * cbrt(lambda N / V)); traversed by the 3D-DDA of Amanatides & Woo 1987, "A fast
// voxel traversal algorithm for ray tracing", with a small per-ray mailbox against re-testing
// primitives that span several cells. Cost per ray: one step per cell pierced plus the cells'
// primitives; the walk ends at the first cell whose exit lies beyond the closest hit.

#include "accel/accel.h"
#include "accel/window_leaf.h"
#include "intersect/box/slabs.h"

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

/// A uniform grid over the union of the primitive boxes; cell (x, y, z) has linear index
/// x + res[0] * (y + res[1] * z) and holds cell_prims[cell_start[i], cell_start[i + 1]).
struct Grid {
    using Config = GridConfig;

    std::array<std::uint32_t, 3> res{0, 0, 0};  ///< cells per axis (all 0 when no primitive)
    Bounds3f box;                               ///< the grid's box: union of non-empty prim boxes
    Vec3f cell_size;                            ///< box extent / res per axis
    Vec3f inv_cell_size;                        ///< 1 / cell_size (0 on an axis of zero extent)
    std::vector<std::uint32_t> cell_start;      ///< CSR offsets, size cells + 1
    std::vector<std::uint32_t> cell_prims;      ///< primitive ids, cell by cell, ascending per cell
    std::vector<bool> prim_present;             ///< per primitive id: its box passes is_usable_box

    /// Number of cells.
    std::size_t cell_count() const { return static_cast<std::size_t>(res[0]) * res[1] * res[2]; }

    /// Closest hit: cells are walked front to back and their primitives offered to hit_fn (once
    /// per ray, unless evicted from the 8-entry mailbox); the walk ends once ray.tmax (shrunk by
    /// hit_fn) lies within the current cell. Invalid rays are rejected before any cell.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return closest_hit_by_walk(ray, hit_fn, stats, [&](Rayf& r, auto&& visit) {
            return walk<IsRobust>(r, stats, visit);
        });
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return any_hit_by_walk(ray, hit_fn, stats, [&](Rayf& r, auto&& visit) {
            return walk<IsRobust>(r, stats, visit);
        });
    }

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
    /// Recently tested primitive ids of one ray (lives on the stack: thread-safe).
    struct Mailbox {
        std::array<std::uint32_t, 8> ids;
        std::uint32_t next = 0;
        Mailbox() { ids.fill(std::numeric_limits<std::uint32_t>::max()); }
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

    /// The 3D-DDA. visit(id) is called for every primitive of each cell pierced (front to back)
    /// and returns true to stop. The walk ends after a cell once ray.tmax <= that cell's exit.
    template <bool IsRobust, class S, class Visit>
    bool walk(Rayf& ray, S& stats, Visit&& visit) const {
        if (!is_valid(ray) || cell_start.empty()) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        float t0 = ray.tmin, t1 = ray.tmax;
        if (!clip_slabs<IsRobust>(box.lo, box.hi, sr, t0, t1)) {
            return false;
        }
        // Entry cell from the entry point; t_next[a] is where the ray leaves it along axis a.
        const Vec3f entry = ray.at(t0);
        std::array<int, 3> cell{}, step{}, out{};
        std::array<float, 3> t_next{};
        for (std::size_t a = 0; a < 3; ++a) {
            const int last = static_cast<int>(res[a]) - 1;
            const float c = std::floor((entry[a] - box.lo[a]) * inv_cell_size[a]);
            cell[a] = c > static_cast<float>(last) ? last : (c > 0.0f ? static_cast<int>(c) : 0);
            if (ray.dir[a] > 0.0f) {
                step[a] = 1;
                out[a] = last + 1;
            } else if (ray.dir[a] < 0.0f) {
                step[a] = -1;
                out[a] = -1;
            }
            t_next[a] = next_crossing(sr, a, cell[a], step[a]);
        }
        Mailbox mailbox;
        for (;;) {
            stats.count_node();
            const std::size_t axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                                           : (t_next[1] < t_next[2] ? 1 : 2);
            const float t_exit = t_next[axis] < t1 ? t_next[axis] : t1;
            const std::size_t index = static_cast<std::size_t>(cell[0]) +
                                      res[0] * (static_cast<std::size_t>(cell[1]) +
                                                res[1] * static_cast<std::size_t>(cell[2]));
            for (std::uint32_t i = cell_start[index]; i < cell_start[index + 1]; ++i) {
                const std::uint32_t id = cell_prims[i];
                if (!mailbox.seen_or_add(id) && visit(id)) {
                    return true;
                }
            }
            // A hit inside this cell cannot be beaten by a later cell; also stop at the window.
            if (ray.tmax <= t_exit || t_exit >= t1 || t_next[axis] > ray.tmax) {
                return false;
            }
            cell[axis] += step[axis];
            if (cell[axis] == out[axis]) {
                return false;
            }
            t_next[axis] = next_crossing(sr, axis, cell[axis], step[axis]);
        }
    }

    /// The t where the ray leaves cell index c along axis a (+inf when it never does).
    float next_crossing(const SlabRay<float>& sr, std::size_t a, int c, int s) const {
        if (s == 0) {
            return std::numeric_limits<float>::infinity();
        }
        const int plane = s > 0 ? c + 1 : c;
        const float x = box.lo[a] + static_cast<float>(plane) * cell_size[a];
        return (x - sr.org[a]) * sr.inv_dir[a];
    }
};

static_assert(Accel<Grid>);

}  // namespace rtlab
