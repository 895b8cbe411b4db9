#pragma once
// A RayBlock (trace/wide_soa.h) for tests: every ray of a span in one block, each ray's answer
// and traversal counts kept apart.

#include "accel/accel.h"
#include "intersect/ray.h"

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace rtlab::test {

/// Found is SlotHit for closest-hit blocks, std::uint32_t (the slot) for any-hit ones.
template <class Found>
struct KeepAllBlock {
    std::span<const Rayf> rays;
    std::size_t begin = 0;
    std::size_t end = rays.size();
    std::vector<std::optional<Found>> found = std::vector<std::optional<Found>>(rays.size());
    std::vector<TraversalStats> counts = std::vector<TraversalStats>(rays.size());

    bool take(std::size_t i, Rayf& ray) const {
        ray = rays[i];
        return true;
    }
    void put(std::size_t i, const Found& f) { found[i] = f; }
    TraversalStats& stats(std::size_t i) { return counts[i]; }
};

}  // namespace rtlab::test
