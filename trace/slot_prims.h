#pragma once
// A method's prepared primitives in a structure's leaf-slot order, with their ids: the leaf data
// of the generic leaf kernel (trace/leaf_kernel.h) of every method without a hand-written SIMD
// kernel. Leaves are then tested without an id indirection, as
// madmann91/bvh's examples permute their triangles.

#include "accel/accel.h"
#include "base/large_pages.h"
#include "intersect/lanes.h"
#include "intersect/method.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace rtlab {

namespace detail {
struct NoLanes {};
/// M::Lanes for a method with lanes, else NoLanes, as a std::type_identity.
template <class M>
auto lanes_of() {
    if constexpr (HasLanes<M>) {
        return std::type_identity<typename M::Lanes>{};
    } else {
        return std::type_identity<NoLanes>{};
    }
}
}  // namespace detail

/// M's prepared primitives by slot and the id of each slot (the caller's, e.g. a global
/// primitive id); for a method with lanes also in lane groups, slot s in lane s % lane_count of
/// group s / lane_count.
template <class M>
struct SlotPrims {
    using Lanes = typename decltype(detail::lanes_of<M>())::type;

    LargeVector<typename M::Prepared> prims;  ///< slot s's primitive
    LargeVector<std::uint32_t> ids;           ///< slot s's id
    LargeVector<Lanes> lanes;                 ///< HasLanes: the lane groups

    /// Number of slots.
    std::uint32_t size() const { return static_cast<std::uint32_t>(prims.size()); }
    /// The id stored for slot s.
    std::uint32_t id(std::uint32_t s) const { return ids[s]; }
    /// Bytes of the primitives and ids.
    std::size_t bytes() const {
        return prims.size() * sizeof(typename M::Prepared) + ids.size() * sizeof(std::uint32_t) +
               (HasLanes<M> ? lanes.size() * sizeof(Lanes) : 0);
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
    if constexpr (HasLanes<M>) {
        q.lanes.resize((q.prims.size() + lane_count - 1) / lane_count);
        for (std::size_t s = 0; s < q.prims.size(); ++s) {
            M::set_lane(q.lanes[s / lane_count], static_cast<unsigned>(s % lane_count), q.prims[s]);
        }
    }
    return q;
}

}  // namespace rtlab
