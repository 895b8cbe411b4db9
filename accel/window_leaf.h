#pragma once
// The closest-hit and any-hit adapters shared by structures whose traversal is a front-to-back
// leaf walk that may reach one primitive from several leaves or cells (kd-tree, uniform grid).
// The walk calls visit(id) for each primitive of each leaf it reaches and stops when visit
// returns true; it ends by itself once ray.tmax (shrunk by closest hits) lies within the current
// leaf, so a hit beyond the current leaf's window never ends the walk early. Templates only:
// both adapters inline into the walk, at no cost per ray beyond the walk itself.

#include "accel/accel.h"

#include <cstdint>

namespace rtlab {

/// Closest hit over a leaf walk: offers every primitive walk(ray, visit) reaches to hit_fn
/// (which shrinks ray.tmax), counting each test, and returns whether any was hit.
template <ClosestHitFn F, StatsSink S, class Walk>
bool closest_hit_by_walk(Rayf& ray, F& hit_fn, S& stats, Walk&& walk) {
    bool hit = false;
    walk(ray, [&](std::uint32_t id) {
        stats.count_prim();
        hit = hit_fn(id, ray) || hit;
        return false;
    });
    return hit;
}

/// Any hit over a leaf walk: walks a copy of ray (hit_fn sees the caller's ray) and stops at the
/// first primitive hit_fn reports as blocking, counting each test.
template <AnyHitFn F, StatsSink S, class Walk>
bool any_hit_by_walk(const Rayf& ray, F& hit_fn, S& stats, Walk&& walk) {
    Rayf r = ray;
    return walk(r, [&](std::uint32_t id) {
        stats.count_prim();
        return static_cast<bool>(hit_fn(id, ray));
    });
}

/// intersect and occluded of a structure Derived whose traversal is such a leaf walk, written as
/// Derived::walk_ids<IsRobust>(ray, stats, visit) (a friend of this base when private): it checks
/// the ray (an invalid one reaches nothing), counts it and calls visit(id) for each primitive of
/// each leaf or cell it reaches front to back, stopping when visit returns true.
template <class Derived>
struct LeafWalkQueries {
    /// Closest hit: every primitive the walk reaches is offered to hit_fn, which shrinks
    /// ray.tmax; the walk ends once ray.tmax lies within the current leaf or cell.
    template <bool IsRobust = false, ClosestHitFn F, StatsSink S = NoStats>
    bool intersect(Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return closest_hit_by_walk(ray, hit_fn, stats, [&](Rayf& r, auto&& visit) {
            return derived().template walk_ids<IsRobust>(r, stats, visit);
        });
    }

    /// Any hit: stops at the first primitive hit_fn reports as blocking.
    template <bool IsRobust = false, AnyHitFn F, StatsSink S = NoStats>
    bool occluded(const Rayf& ray, F&& hit_fn, S&& stats = {}) const {
        return any_hit_by_walk(ray, hit_fn, stats, [&](Rayf& r, auto&& visit) {
            return derived().template walk_ids<IsRobust>(r, stats, visit);
        });
    }

    friend bool operator==(const LeafWalkQueries&, const LeafWalkQueries&) = default;

private:
    const Derived& derived() const { return static_cast<const Derived&>(*this); }
};

}  // namespace rtlab
