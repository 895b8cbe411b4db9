#pragma once
// Ray sets for benchmarks and checks, deterministic for (scene, kind, count, seed):
//   primary: camera rays through uniformly random image points;
//   shadow:  from primary-ray hit points towards a random light (or a random scene point when the
//            scene has no lights), t in [0, 1] spanning the segment;
//   diffuse: from primary-ray hit points, cosine-distributed about the normal facing the eye;
//   random:  origins uniform in the scene box grown by 10 %, directions uniform on the sphere.
// Secondary rays start at p + n * offset with offset = max(1e-5 * scene diagonal,
// 64 * FLT_EPSILON * max|p_i|): scale-aware, so far-from-origin scenes do not self-intersect.

#include "intersect/ray.h"
#include "scene/scene.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace rtlab {

/// The kinds of ray set.
enum class RayKind { primary, shadow, diffuse, random };

/// Lower-case name of a kind.
std::string_view to_string(RayKind k);

/// Parses a kind name; throws std::invalid_argument for anything else.
RayKind parse_ray_kind(std::string_view name);

/// Makes `count` rays of `kind` for `scene`. Shadow and diffuse rays need primary hits: throws
/// rtlab::Error when the camera sees nothing.
std::vector<Rayf> make_rays(const Scene& scene,
                            RayKind kind,
                            std::size_t count,
                            std::uint64_t seed);

}  // namespace rtlab
