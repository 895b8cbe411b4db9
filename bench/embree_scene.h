#pragma once
// An rtlab Scene as an Embree 3 scene, the baseline for the traversal and build benchmarks:
// every mesh as one RTC_GEOMETRY_TYPE_TRIANGLE geometry and all analytic spheres as one
// RTC_GEOMETRY_TYPE_SPHERE_POINT geometry (centre and radius), so Embree sees exactly the
// primitives our structures see. Other primitive types have no Embree counterpart here: the
// constructor refuses them. Only compiled when CMake finds Embree (bench/CMakeLists.txt).

#include "intersect/ray.h"
#include "scene/scene.h"

#include <cstdint>
#include <embree3/rtcore.h>
#include <span>

namespace rtlab::bench {

/// The process-wide Embree device (default configuration: all threads, through TBB).
RTCDevice embree_device();

/// One Embree scene over a Scene's triangles and spheres.
class EmbreeScene {
public:
    /// Copies s's meshes and spheres into Embree geometry with build quality q (not yet built).
    /// Throws std::invalid_argument when s holds polygons, boxes, oriented boxes or implicits.
    EmbreeScene(const Scene& s, RTCBuildQuality q);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// Builds the BVH (rtcCommitScene) and returns its wall time in milliseconds; throws
    /// std::runtime_error when Embree reports an error.
    double commit();

    /// Closest hit distance per ray (t[i] for rays[i], +inf on a miss) through rtcIntersect1,
    /// parallelised exactly like SceneTracer: tbb::parallel_for over rays, 256 rays per task.
    void intersect(std::span<const Rayf> rays, std::span<float> t) const;

    /// Occlusion per ray (1 when something blocks rays[i]'s window, else 0) through rtcOccluded1,
    /// parallelised like intersect().
    void occluded(std::span<const Rayf> rays, std::span<std::uint8_t> blocked) const;

private:
    RTCScene scene_ = nullptr;
};

}  // namespace rtlab::bench
