#pragma once
// An rtlab Scene as an Embree 3 scene, the baseline for the traversal and build benchmarks:
// every mesh as one RTC_GEOMETRY_TYPE_TRIANGLE geometry and all analytic spheres as one
// RTC_GEOMETRY_TYPE_SPHERE_POINT geometry (centre and radius), so Embree sees exactly the
// primitives our structures see. Other primitive types have no Embree counterpart here: the
// constructor refuses them. Only compiled when CMake finds Embree (bench/CMakeLists.txt).

#include "intersect/ray.h"
#include "scene/scene.h"
#include "trace/ray_gen.h"

#include <cstdint>
#include <embree3/rtcore.h>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace benchmark {
class State;
}  // namespace benchmark

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

    /// Bytes Embree allocated for this scene (geometry buffers and BVH, counted through
    /// rtcSetDeviceMemoryMonitorFunction from construction to the end of commit(); Embree's own
    /// figure, so it includes its vertex and index copies).
    std::int64_t bytes() const { return bytes_; }

    /// Closest hit distance per ray (t[i] for rays[i], +inf on a miss) through rtcIntersect1,
    /// parallelised exactly like SceneTracer: tbb::parallel_for over rays, 256 rays per task.
    void intersect(std::span<const Rayf> rays, std::span<float> t) const;

    /// Occlusion per ray (1 when something blocks rays[i]'s window, else 0) through rtcOccluded1,
    /// parallelised like intersect().
    void occluded(std::span<const Rayf> rays, std::span<std::uint8_t> blocked) const;

private:
    RTCScene scene_ = nullptr;
    std::int64_t bytes_ = 0;  ///< allocated bytes, as bytes()
};

/// One pass of an Embree scene over a ray set with its output buffers: occluded for shadow rays,
/// intersect for the others.
struct EmbreePass {
    explicit EmbreePass(std::size_t n) : t(n), blocked(n) {}
    void run(const EmbreeScene& e, std::span<const Rayf> rays, RayKind kind);
    std::vector<float> t;
    std::vector<std::uint8_t> blocked;
};

/// A committed Embree scene and the time its build took.
struct BuiltScene {
    std::unique_ptr<EmbreeScene> scene;
    double build_ms = 0;
};

/// The Embree scene of benchmark scene `scene` (bench/trace_fixture.h) at quality q, built once
/// per process (the timed commit in build_ms).
const BuiltScene& cached_embree_scene(const std::string& scene, RTCBuildQuality q);

/// How Embree and our bvh:binned tracer compare on the first 1000 rays of a set.
struct Agreement {
    std::size_t checked = 0;  ///< rays compared
    std::size_t agree = 0;    ///< rays on which both agree
    std::size_t hits = 0;     ///< agreeing rays that hit (shadow: are blocked)
};

/// Traces the first 1000 rays of (scene, kind) with e and with bvh:binned: a ray agrees when
/// both miss, or both hit with |t_embree - t_ours| <= 1e-4 |t_ours| (shadow: same occlusion).
Agreement embree_agreement(const EmbreeScene& e, const std::string& scene, RayKind kind);

/// An Embree build quality the baselines run, with its name in benchmark names.
struct EmbreeQuality {
    const char* name;
    RTCBuildQuality quality;
};
inline constexpr EmbreeQuality embree_qualities[] = {{"medium", RTC_BUILD_QUALITY_MEDIUM},
                                                     {"high", RTC_BUILD_QUALITY_HIGH}};

/// The primitives of s an EmbreeScene holds: its triangles and spheres.
std::size_t embree_primitive_count(const Scene& s);

/// The body of an Embree trace benchmark on the rays of (scene, kind) at quality q: the scene
/// from cached_embree_scene, embree_agreement on its first 1000 rays (more than 5 disagreements
/// skip the benchmark with an error), then each iteration traces every ray (rtcOccluded1 for
/// shadow rays, else rtcIntersect1). Sets the counters rays/s, build_ms, prims, agree and
/// agree_hits; returns the built scene, or nullptr when the benchmark was skipped.
const BuiltScene* run_embree_trace(benchmark::State& state,
                                   const std::string& scene,
                                   RTCBuildQuality q,
                                   RayKind kind);

}  // namespace rtlab::bench
