#pragma once
// A scene's primitives grouped by type, each group prepared for one intersection method and
// indexed by its own acceleration structure. The method and the structure are chosen once per
// scene at run time; tracing visits both once per batch, so the per-ray loop is fully static.

#include "accel/any_accel.h"
#include "base/large_pages.h"
#include "trace/method_families.h"
#include "trace/triangle_soa.h"

#include <cstdint>
#include <optional>
#include <tuple>
#include <variant>
#include <vector>

namespace rtlab {

/// The primitives of one type, prepared for method M, with their global ids and a structure.
template <class M>
struct PrimSet {
    using Method = M;
    LargeVector<typename M::Prepared> prims;  ///< local index = structure's primitive id
    std::vector<std::uint32_t> ids;           ///< global primitive id of each local one
    AnyAccel accel;                           ///< built over M::bounds of prims
    /// The triangles in the structure's leaf-slot order (empty unless M has a leaf kernel and the
    /// structure offers whole leaves with soa_leaves set; see trace/triangle_soa.h).
    TriangleSoA soa;
    /// prims in the structure's leaf-slot order, slot_prims[s] = prims[prim_ids[s]] (empty unless
    /// the structure offers whole leaves with soa_leaves set and M has no leaf kernel): leaves are
    /// then tested without an id indirection, as madmann91/bvh's examples permute their triangles.
    LargeVector<typename M::Prepared> slot_prims;
    /// The global id of every slot of slot_prims (one read for a hit instead of two).
    LargeVector<std::uint32_t> slot_ids;
};

/// The SoaLayout of M's leaf kernel, for the methods that have one.
template <class M>
inline constexpr std::optional<SoaLayout> soa_layout_of = std::nullopt;
template <>
inline constexpr std::optional<SoaLayout> soa_layout_of<MollerTrumbore<float>> = SoaLayout::edges;
template <>
inline constexpr std::optional<SoaLayout> soa_layout_of<Watertight<float>> = SoaLayout::vertices;

namespace detail {
template <class List>
struct PrimSetVariant;
template <class... Ms>
struct PrimSetVariant<std::tuple<Ms...>> {
    using type = std::variant<PrimSet<Ms>...>;
};
}  // namespace detail

/// Every (primitive type, method) combination a scene can be traced with: a PrimSet<M> for every
/// method M of every family in MethodFamilyTable.
using AnyPrimSet = typename detail::PrimSetVariant<AllFamilyMethods>::type;

}  // namespace rtlab
