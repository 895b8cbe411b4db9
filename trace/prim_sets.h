#pragma once
// A scene's primitives grouped by type, each group prepared for one intersection method and
// indexed by its own acceleration structure. The method and the structure are chosen once per
// scene at run time; tracing visits both once per batch, so the per-ray loop is fully static.

#include "accel/any_accel.h"
#include "base/large_pages.h"
#include "trace/method_families.h"
#include "trace/sphere_soa.h"
#include "trace/triangle_soa.h"

#include <cstdint>
#include <optional>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

namespace rtlab {

/// The SoaLayout of M's triangle leaf kernel, for the triangle methods that have one.
template <class M>
inline constexpr std::optional<SoaLayout> soa_layout_of = std::nullopt;
template <>
inline constexpr std::optional<SoaLayout> soa_layout_of<MollerTrumbore<float>> = SoaLayout::edges;
template <>
inline constexpr std::optional<SoaLayout> soa_layout_of<Watertight<float>> = SoaLayout::vertices;

/// The leaf data of a method without a SIMD leaf kernel: always empty.
struct NoLeafSoa {
    std::uint32_t size() const { return 0; }
};

namespace detail {
template <class M>
struct LeafSoaOf {
    using type = NoLeafSoa;
};
template <>
struct LeafSoaOf<MollerTrumbore<float>> {
    using type = TriangleSoA;
};
template <>
struct LeafSoaOf<Watertight<float>> {
    using type = TriangleSoA;
};
template <>
struct LeafSoaOf<SphereStable<float>> {
    using type = SphereSoA;
};
}  // namespace detail

/// The slot-ordered leaf data of M's SIMD leaf kernel: TriangleSoA (Möller–Trumbore, watertight;
/// trace/triangle_soa.h), SphereSoA (SphereStable<float>; trace/sphere_soa.h), else NoLeafSoa.
template <class M>
using LeafSoa = typename detail::LeafSoaOf<M>::type;

/// True when M has a SIMD leaf kernel over LeafSoa<M>.
template <class M>
inline constexpr bool has_leaf_kernel = !std::is_same_v<LeafSoa<M>, NoLeafSoa>;

/// The primitives of one type, prepared for method M, with their global ids and a structure.
template <class M>
struct PrimSet {
    using Method = M;
    LargeVector<typename M::Prepared> prims;  ///< local index = structure's primitive id
    std::vector<std::uint32_t> ids;           ///< global primitive id of each local one
    AnyAccel accel;                           ///< built over M::bounds of prims
    /// The primitives in the structure's leaf-slot order for M's leaf kernel (empty unless M has
    /// one and the structure offers whole leaves with soa_leaves set).
    LeafSoa<M> soa;
    /// prims in the structure's leaf-slot order, slot_prims[s] = prims[prim_ids[s]] (empty unless
    /// the structure offers whole leaves with soa_leaves set and M has no leaf kernel): leaves are
    /// then tested without an id indirection, as madmann91/bvh's examples permute their triangles.
    LargeVector<typename M::Prepared> slot_prims;
    /// The global id of every slot of slot_prims (one read for a hit instead of two).
    LargeVector<std::uint32_t> slot_ids;
};

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
