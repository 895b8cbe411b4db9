#pragma once
// A scene's primitives grouped by type, each group prepared for one intersection method and
// indexed by its own acceleration structure. The method and the structure are chosen once per
// scene at run time; tracing visits both once per batch, so the per-ray loop is fully static.

#include "accel/any_accel.h"
#include "intersect/box/aabb.h"
#include "intersect/box/obb.h"
#include "intersect/implicit/methods.h"
#include "intersect/polygon/crossing_count.h"
#include "intersect/polygon/winding_number.h"
#include "intersect/sphere/algebraic.h"
#include "intersect/sphere/geometric.h"
#include "intersect/sphere/stable.h"
#include "intersect/triangle/badouel.h"
#include "intersect/triangle/moller_trumbore.h"
#include "intersect/triangle/segura_feito.h"
#include "intersect/triangle/watertight.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtlab {

/// The primitives of one type, prepared for method M, with their global ids and a structure.
template <class M>
struct PrimSet {
    using Method = M;
    std::vector<typename M::Prepared> prims;  ///< local index = structure's primitive id
    std::vector<std::uint32_t> ids;           ///< global primitive id of each local one
    AnyAccel accel;                           ///< built over M::bounds of prims
};

/// Every (primitive type, method) combination a scene can be traced with.
using AnyPrimSet = std::variant<PrimSet<MollerTrumbore<float>>,
                                PrimSet<Badouel<float>>,
                                PrimSet<SeguraFeito<float>>,
                                PrimSet<Watertight<float>>,
                                PrimSet<SphereGeometric<float>>,
                                PrimSet<SphereAlgebraic<float>>,
                                PrimSet<SphereStable<float>>,
                                PrimSet<PolygonCrossing<float>>,
                                PrimSet<PolygonWinding<float>>,
                                PrimSet<AabbSlabs<float>>,
                                PrimSet<AabbSlabsRobust<float>>,
                                PrimSet<ObbSlabs<float>>,
                                PrimSet<ImplicitClosedForm<Torus, float>>,
                                PrimSet<ImplicitNewton<Torus, float>>,
                                PrimSet<ImplicitLaguerre<Torus, float>>,
                                PrimSet<ImplicitClosedForm<TangleCube, float>>,
                                PrimSet<ImplicitNewton<TangleCube, float>>,
                                PrimSet<ImplicitLaguerre<TangleCube, float>>>;

/// The method names per primitive family, default first, as accepted by --method.
struct MethodFamily {
    std::string_view family;                ///< "triangle", "sphere", "polygon", ...
    std::vector<std::string_view> methods;  ///< method names; methods[0] is the default
};

/// Every family with its methods (triangle, sphere, polygon, box, obb, implicit).
const std::vector<MethodFamily>& method_families();

}  // namespace rtlab
