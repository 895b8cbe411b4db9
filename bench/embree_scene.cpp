// EmbreeScene: geometry upload, build and per-ray queries through the Embree 3 C API.
#include "bench/embree_scene.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rtlab::bench {

namespace {

// Rays per TBB task: the grain SceneTracer uses (trace/scene_tracer.cpp), so both sides of the
// comparison split the work the same way.
constexpr std::size_t grain = 256;

void check_device(const char* what) {
    const RTCError e = rtcGetDeviceError(embree_device());
    if (e != RTC_ERROR_NONE) {
        throw std::runtime_error(std::string("embree: ") + what + " failed with error " +
                                 std::to_string(static_cast<int>(e)));
    }
}

// Bytes Embree holds, from its memory monitor: allocations add, frees subtract.
std::atomic<std::int64_t> embree_allocated{0};

bool monitor(void*, ssize_t bytes, bool) {
    embree_allocated += bytes;
    return true;
}

RTCRay to_embree(const Rayf& r) {
    RTCRay e{};
    e.org_x = r.org.x;
    e.org_y = r.org.y;
    e.org_z = r.org.z;
    e.tnear = r.tmin;
    e.dir_x = r.dir.x;
    e.dir_y = r.dir.y;
    e.dir_z = r.dir.z;
    e.time = 0;
    e.tfar = r.tmax;
    e.mask = 0xFFFFFFFFu;
    e.id = 0;
    e.flags = 0;
    return e;
}

}  // namespace

RTCDevice embree_device() {
    static const RTCDevice device = [] {
        RTCDevice d = rtcNewDevice(nullptr);
        rtcSetDeviceMemoryMonitorFunction(d, monitor, nullptr);
        // Warm-up: the first builds in a process start Embree's TBB workers and allocators; one
        // tiny build (a triangle and a sphere) here keeps that cost out of every measured build.
        RTCScene s = rtcNewScene(d);
        RTCGeometry tri = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* tv = static_cast<float*>(rtcSetNewGeometryBuffer(
            tri, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3));
        const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        std::copy(corners, corners + 9, tv);
        auto* ti = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            tri, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 1));
        ti[0] = 0;
        ti[1] = 1;
        ti[2] = 2;
        RTCGeometry sph = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* sv = static_cast<float*>(rtcSetNewGeometryBuffer(
            sph, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
        const float ball[4] = {0, 0, 2, 1};
        std::copy(ball, ball + 4, sv);
        for (RTCGeometry g : {tri, sph}) {
            rtcCommitGeometry(g);
            rtcAttachGeometry(s, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(s);
        rtcReleaseScene(s);
        return d;
    }();
    return device;
}

EmbreeScene::EmbreeScene(const Scene& s, RTCBuildQuality q) {
    if (!s.polygons.empty() || !s.boxes.empty() || !s.obbs.empty() || !s.implicits.empty()) {
        throw std::invalid_argument(
            "EmbreeScene: only triangle meshes and spheres have an Embree counterpart");
    }
    RTCDevice device = embree_device();
    bytes_ = -embree_allocated.load();
    scene_ = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene_, q);
    for (const MeshObject& m : s.meshes) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(g, q);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              m.mesh.positions.size()));
        for (std::size_t i = 0; i < m.mesh.positions.size(); ++i) {
            v[3 * i + 0] = m.mesh.positions[i].x;
            v[3 * i + 1] = m.mesh.positions[i].y;
            v[3 * i + 2] = m.mesh.positions[i].z;
        }
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), m.mesh.triangles.size()));
        for (std::size_t i = 0; i < m.mesh.triangles.size(); ++i) {
            for (std::size_t k = 0; k < 3; ++k) {
                idx[3 * i + k] = m.mesh.triangles[i][k];
            }
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
    }
    if (!s.spheres.empty()) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        rtcSetGeometryBuildQuality(g, q);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), s.spheres.size()));
        for (std::size_t i = 0; i < s.spheres.size(); ++i) {
            v[4 * i + 0] = s.spheres[i].center.x;
            v[4 * i + 1] = s.spheres[i].center.y;
            v[4 * i + 2] = s.spheres[i].center.z;
            v[4 * i + 3] = s.spheres[i].radius;
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
    }
    try {
        check_device("geometry upload");
    } catch (...) {
        rtcReleaseScene(scene_);  // the destructor does not run when the constructor throws
        throw;
    }
}

EmbreeScene::~EmbreeScene() {
    rtcReleaseScene(scene_);
}

double EmbreeScene::commit() {
    const auto t0 = std::chrono::steady_clock::now();
    rtcCommitScene(scene_);
    const auto t1 = std::chrono::steady_clock::now();
    check_device("rtcCommitScene");
    bytes_ += embree_allocated.load();
    return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

void EmbreeScene::intersect(std::span<const Rayf> rays, std::span<float> t) const {
    if (t.size() != rays.size()) {
        throw std::invalid_argument("EmbreeScene::intersect: t and rays differ in size");
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          RTCIntersectContext ctx;
                          rtcInitIntersectContext(&ctx);
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              RTCRayHit rh{};
                              rh.ray = to_embree(rays[i]);
                              rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                              rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                              rtcIntersect1(scene_, &ctx, &rh);
                              t[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID
                                         ? rh.ray.tfar
                                         : std::numeric_limits<float>::infinity();
                          }
                      });
}

void EmbreeScene::occluded(std::span<const Rayf> rays, std::span<std::uint8_t> blocked) const {
    if (blocked.size() != rays.size()) {
        throw std::invalid_argument("EmbreeScene::occluded: blocked and rays differ in size");
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          RTCIntersectContext ctx;
                          rtcInitIntersectContext(&ctx);
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              RTCRay ray = to_embree(rays[i]);
                              rtcOccluded1(scene_, &ctx, &ray);
                              // rtcOccluded1 sets tfar to -inf when the ray is blocked.
                              blocked[i] =
                                  ray.tfar == -std::numeric_limits<float>::infinity() ? 1 : 0;
                          }
                      });
}

void EmbreePass::run(const EmbreeScene& e, std::span<const Rayf> rays, RayKind kind) {
    if (kind == RayKind::shadow) {
        e.occluded(rays, blocked);
        benchmark::DoNotOptimize(blocked.data());
    } else {
        e.intersect(rays, t);
        benchmark::DoNotOptimize(t.data());
    }
}

std::size_t embree_primitive_count(const Scene& s) {
    std::size_t n = s.spheres.size();
    for (const MeshObject& m : s.meshes) {
        n += m.mesh.triangle_count();
    }
    return n;
}

}  // namespace rtlab::bench
