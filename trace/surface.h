#pragma once
// The second phase of a hit: from the lean {t, u, v, prim} to the surface point and normal.

#include "intersect/hit.h"
#include "intersect/ray.h"
#include "scene/scene.h"

#include <cstdint>
#include <vector>

namespace rtlab {

/// Geometric surface data at a hit.
struct SurfacePoint {
    Vec3f p;                 ///< hit point ray.at(t)
    Vec3f n;                 ///< unit geometric normal, flipped to face the incoming ray
    bool front_face = true;  ///< false when the ray arrived from the side the normal points away
    std::uint32_t material = 0;
};

/// Surface point and normal of a valid hit of `ray` in `scene`; `base` is primitive_id_base(scene).
SurfacePoint surface_at(const Scene& scene,
                        const std::vector<std::uint32_t>& base,
                        const Hit& hit,
                        const Rayf& ray);

}  // namespace rtlab
