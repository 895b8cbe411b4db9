#pragma once
// A scene's primitives grouped by type, each group prepared for one intersection method and
// indexed by its own acceleration structure. The method and the structure are chosen once per
// scene at run time; tracing visits both once per batch, so the per-ray loop is fully static.

#include "accel/any_accel.h"
#include "base/large_pages.h"
#include "trace/leaf_kernel.h"
#include "trace/method_families.h"

#include <cstdint>
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
    /// The primitives in the structure's leaf-slot order as M's leaf kernel tests them
    /// (trace/leaf_kernel.h; empty unless the structure offers whole leaves and the tracer asks
    /// for slot-ordered leaves).
    LeafData<M> soa;
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
