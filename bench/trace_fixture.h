#pragma once
// Shared by the traversal, build and Embree suites: the benchmark scenes (by name), their fixed
// ray sets and built tracers, cached once per process so every structure traces the same rays.
//
// Scene names encode the generator and its size:
//   flake_mesh<k>     SPD sphere flake of size k, tessellated (uv:16x8), WITHOUT the floor;
//   flake_spheres<k>  the same flake as analytic spheres, WITHOUT the floor;
//   flake_meshfloor<k> the tessellated flake WITH its floor as two triangles (a second mesh);
//   soup              random triangle soup, size 6 (65536 triangles);
//   stadium           teapot in a stadium, size 5 (12300 triangles);
//   mount             fractal terrain, size 6 (8192 triangles) plus 4 analytic spheres.
// The flake generator adds a floor polygon (two triangles as mesh). Embree has no polygon
// geometry, so flake_mesh and flake_spheres drop the floor: our structures and Embree then see
// exactly the same primitives, and flake_mesh<k> and flake_spheres<k> differ only in tessellation.

#include "intersect/bounds.h"
#include "intersect/ray.h"
#include "scene/scene.h"
#include "trace/ray_gen.h"
#include "trace/scene_tracer.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace rtlab::bench {

/// Rays per (scene, kind) set: 16384, or 4096 in quick mode.
std::size_t bench_ray_count();

/// Every ray kind, in report order.
inline constexpr std::array<RayKind, 4> bench_ray_kinds{RayKind::primary, RayKind::shadow,
                                                        RayKind::diffuse, RayKind::random};

/// A generated scene and one fixed ray set per kind (seed 1), built once per process.
struct BenchScene {
    Scene scene;                                ///< the primitives every structure traces
    std::map<RayKind, std::vector<Rayf>> rays;  ///< bench_ray_count() rays per kind
};

/// The scene called `name` (see the top of this file); throws std::invalid_argument for others.
const BenchScene& bench_scene(const std::string& name);

/// The traversal scenes to register: quick mode keeps flake size 2 only and leaves out the
/// stadium.
std::vector<std::string> trace_scene_names();

/// A SceneTracer for (scene, accel) with default methods, built once per process.
const SceneTracer& bench_tracer(const std::string& scene, const std::string& accel);

/// One pass of a tracer over a ray set with its output buffers: occluded for shadow rays,
/// intersect for the others, counting into *stats when given.
struct TracePass {
    explicit TracePass(std::size_t n) : hits(n), blockers(n) {}
    void run(const SceneTracer& t,
             const std::vector<Rayf>& rays,
             RayKind kind,
             TraversalStats* stats = nullptr);
    std::vector<Hit> hits;
    std::vector<std::uint32_t> blockers;
};

/// Traces rays with t once per state iteration (occluded for shadow rays, intersect for the
/// others; the timed loop), then once more counting; returns that pass's counts.
TraversalStats time_and_count(benchmark::State& state,
                              const SceneTracer& t,
                              const std::vector<Rayf>& rays,
                              RayKind kind);

/// Soup size factors of the build sweep: 1024 * 2^sf triangles, up to ~1e6 (quick: 16384).
std::vector<int> build_soup_sizes();

/// The triangle soup of size sf (1024 * 2^sf triangles, seed 1), built once per process.
const Scene& build_soup(int sf);

/// Triangle bounds of a mesh-only scene, in primitive order.
std::vector<Bounds3f> triangle_bounds(const Scene& s);

/// The exact extents of a mesh-only scene's triangles (by primitive id), computed on call as
/// SceneTracer's builds compute them (`bounds=dop14`); holds its own copy of the triangles.
ExtentFn triangle_extent(const Scene& s);

/// Seconds to build structure `spec` from `in` (build_accel; the structure is freed after the
/// clock stopped).
double seconds_to_build(const std::string& spec, const BuildInput& in);

/// Applies quick mode to a registered benchmark: a 0.02 s minimum time instead of the default.
benchmark::internal::Benchmark* quick_time(benchmark::internal::Benchmark* b);

}  // namespace rtlab::bench
