#pragma once
// A method's prepared primitives in a structure's leaf-slot order, with their ids, and the
// generic leaf kernel over them: the leaf data and kernel of every method without a hand-written
// SIMD kernel (trace/leaf_kernel.h). Leaves are then tested without an id indirection, as
// madmann91/bvh's examples permute their triangles.

#include "accel/accel.h"
#include "base/large_pages.h"
#include "intersect/method.h"
#include "trace/leaf_soa.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace rtlab {

/// M's prepared primitives by slot and the id of each slot (the caller's, e.g. a global
/// primitive id).
template <class M>
struct SlotPrims {
    LargeVector<typename M::Prepared> prims;  ///< slot s's primitive
    LargeVector<std::uint32_t> ids;           ///< slot s's id

    /// Number of slots.
    std::uint32_t size() const { return static_cast<std::uint32_t>(prims.size()); }
    /// The id stored for slot s.
    std::uint32_t id(std::uint32_t s) const { return ids[s]; }
    /// Bytes of the primitives and ids.
    std::size_t bytes() const {
        return prims.size() * sizeof(typename M::Prepared) + ids.size() * sizeof(std::uint32_t);
    }
};

/// The primitives prims[slot_ids[s]] for every slot s, each with the id ids[slot_ids[s]]
/// (slot_ids[s] itself when ids is empty); a padding_slot entry (in no leaf, never tested)
/// repeats the first slot's primitive.
template <class M>
SlotPrims<M> make_slot_prims(std::span<const typename M::Prepared> prims,
                             std::span<const std::uint32_t> slot_ids,
                             std::span<const std::uint32_t> ids) {
    SlotPrims<M> q;
    q.prims.reserve(slot_ids.size());
    q.ids.reserve(slot_ids.size());
    for (const std::uint32_t id : slot_ids) {
        const std::uint32_t i = id == padding_slot ? slot_ids.front() : id;
        q.prims.push_back(prims[i]);
        q.ids.push_back(ids.empty() ? i : ids[i]);
    }
    return q;
}

/// Closest hit among slots [first, first + count): M's scalar test on each slot in order, each
/// hit shrinking ray.tmax; nullopt if none. Inlined into the traversal that calls it. (A
/// lane-parallel version, testing a group of slots with one window and re-testing after a hit,
/// measured 6-24 % slower on bvh8; see docs/architecture.md.)
template <class M>
std::optional<SlotHit> slot_prims_closest(const SlotPrims<M>& q,
                                          std::uint32_t first,
                                          std::uint32_t count,
                                          Rayf& ray,
                                          const RayDataOf<M>& rd) {
    std::optional<SlotHit> best;
    for (std::uint32_t s = first; s < first + count; ++s) {
        if (const auto h = intersect_with<M>(q.prims[s], ray, rd)) {
            ray.tmax = h->t;
            best = SlotHit{s, *h};
        }
    }
    return best;
}

/// The first slot of [first, first + count) that M's scalar any-hit test reports, or nullopt.
template <class M>
std::optional<std::uint32_t> slot_prims_any(const SlotPrims<M>& q,
                                            std::uint32_t first,
                                            std::uint32_t count,
                                            const Rayf& ray,
                                            const RayDataOf<M>& rd) {
    for (std::uint32_t s = first; s < first + count; ++s) {
        if (occluded_with<M>(q.prims[s], ray, rd)) {
            return s;
        }
    }
    return std::nullopt;
}

}  // namespace rtlab
