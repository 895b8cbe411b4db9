#pragma once
// Hits are two-phase: traversal carries the lean {t, u, v, prim}; normals and materials are
// computed only for the winning hit.

#include <cstdint>
#include <limits>

namespace rtlab {

/// Primitive id meaning "no primitive".
inline constexpr std::uint32_t invalid_id = 0xFFFFFFFFu;

/// What one ray-primitive test reports: the ray parameter and two surface parameters whose
/// meaning is the method's (barycentrics for triangles, 0 for spheres unless stated).
template <class T>
struct PrimHit {
    T t;
    T u = 0;
    T v = 0;
};

/// The closest hit found so far along a ray; prim is the caller's original primitive id.
template <class T>
struct BasicHit {
    T t = std::numeric_limits<T>::infinity();
    T u = 0;
    T v = 0;
    std::uint32_t prim = invalid_id;

    /// True when a primitive was hit.
    constexpr bool valid() const { return prim != invalid_id; }
};

using Hit = BasicHit<float>;
using Hitd = BasicHit<double>;

}  // namespace rtlab
