#pragma once
// Brute force: tests every primitive whose box the ray's window meets. The reference every other
// structure is checked against. Cost: O(N) per ray.

#include "accel/accel.h"
#include "intersect/box/slabs.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtlab {

/// The reference structure: a flat list of primitive boxes.
struct BruteForce {
    std::vector<Bounds3f> boxes;  ///< one per primitive id; empty where is_usable_box fails
    Bounds3f scene_bounds;        ///< union of the usable boxes

    /// Copies the usable boxes (others become empty boxes, which no ray meets); O(N).
    [[nodiscard]] static BruteForce build(const BuildInput& in) {
        BruteForce b;
        b.boxes.reserve(in.bounds.size());
        for (const Bounds3f& box : in.bounds) {
            b.boxes.push_back(is_usable_box(box) ? box : Bounds3f{});
            b.scene_bounds.extend(b.boxes.back());
        }
        return b;
    }

    /// Closest hit: every primitive whose box the current window meets is offered to hit_fn.
    /// Invalid rays (NaN, zero direction) are rejected before any test.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        if (!is_valid(ray)) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        bool hit = false;
        for (std::uint32_t i = 0; i < boxes.size(); ++i) {
            float tnear;
            stats.count_node();
            if (slab_hit<true>(boxes[i], sr, ray.tmin, ray.tmax, tnear)) {
                stats.count_prim();
                hit = hit_fn(i, ray) || hit;
            }
        }
        return hit;
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        if (!is_valid(ray)) {
            return false;
        }
        stats.count_ray();
        const SlabRay<float> sr(ray);
        for (std::uint32_t i = 0; i < boxes.size(); ++i) {
            float tnear;
            stats.count_node();
            if (slab_hit<true>(boxes[i], sr, ray.tmin, ray.tmax, tnear)) {
                stats.count_prim();
                if (hit_fn(i, ray)) {
                    return true;
                }
            }
        }
        return false;
    }

    /// Union of all primitive boxes.
    Bounds3f bounds() const { return scene_bounds; }

    /// One "node" per primitive; cost model: N primitive tests per ray.
    AccelInfo info() const {
        AccelInfo i;
        i.nodes = i.leaves = boxes.size();
        i.bytes = boxes.size() * sizeof(Bounds3f);
        i.bytes_per_prim = boxes.empty() ? 0 : static_cast<double>(sizeof(Bounds3f));
        i.sah_cost = static_cast<double>(boxes.size());
        i.refs_per_prim = boxes.empty() ? 0 : 1;
        return i;
    }

    /// Checks that every box is usable or empty and that the scene box contains the usable ones.
    std::string validate() const {
        for (std::uint32_t i = 0; i < boxes.size(); ++i) {
            const Bounds3f& b = boxes[i];
            if (!is_usable_box(b) && !(b == Bounds3f{})) {
                return "primitive " + std::to_string(i) + " has an unusable box that is kept";
            }
            if (is_usable_box(b) && !scene_bounds.contains(b)) {
                return "primitive " + std::to_string(i) + " lies outside the scene bounds";
            }
        }
        return {};
    }

    friend bool operator==(const BruteForce&, const BruteForce&) = default;
};

static_assert(Accel<BruteForce>);

}  // namespace rtlab
