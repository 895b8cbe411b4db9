#pragma once
// Scenes and ray sets of the stability cases that `rtlab stability --fixture` also writes to
// files, so `rtlab trace` can be checked on exactly the rays the suite traces; and the case entry
// points with a subject selection, so the fast tests run only the subjects whose property they
// assert while the report runs the whole matrix.

#include "accel/any_accel.h"
#include "intersect/ray.h"
#include "mesh/triangle_mesh.h"
#include "scene/scene.h"
#include "stability/stability.h"
#include "trace/scene_tracer.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::stab {

/// The watertightness fixture: a closed UV sphere (16 rings, 24 segments, 720 triangles) with
/// shared vertices, each vertex radius 1 +- 0.1 (seeded), so no two faces are coplanar.
TriangleMesh watertight_sphere(std::uint64_t seed);

/// A scene holding just `mesh` (default material, camera framing it).
Scene mesh_scene(TriangleMesh mesh);

/// `count` rays from inside the closed sphere mesh of watertight_sphere (centred at the origin),
/// every one of which must hit it: one third in uniform random directions from points within radius
/// 0.5 of the centre; one third aimed at vertices (half from the exact centre with direction vertex
/// * 2^k, exactly through the vertex, half from random inside points); one third aimed at float
/// points on shared edges (from the centre or random inside points). Deterministic for (mesh,
/// count, seed).
std::vector<Rayf> inside_rays(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed);

/// The structure of tracer's first primitive set (the triangles of a mesh scene).
const AnyAccel& triangle_accel(const SceneTracer& tracer);

/// The adversarial case's closed meshes (scene each): UV spheres of several resolutions with
/// vertex radii jittered by 10 to 45 %, star-shaped around the origin; seeded.
std::vector<Scene> adversarial_scenes(std::uint64_t seed);

/// `count` rays from the kernel of `mesh` (one of adversarial_scenes) that must all hit it, made
/// for the structure `accel` built over it: at vertices (from the exact centre, exactly through
/// them, and from kernel points), at shared-edge points, at points on accel's own planes
/// (stability/structure_planes.h: inside their faces, on face edges, at corners), and starting on
/// or one float beside a plane through the kernel with a direction 1e-9..1e-1 (or exactly 0) along
/// its normal, and from 10 to 1e4 radii away into the kernel. Deterministic for (mesh, structure,
/// count, seed).
std::vector<Rayf> adversarial_rays(const TriangleMesh& mesh,
                                   const AnyAccel& accel,
                                   std::size_t count,
                                   std::uint64_t seed);

/// Which subjects a case runs; the default is the whole matrix (what the report shows).
struct Selection {
    std::vector<std::string> methods;  ///< triangle method names or "exact"; empty: all of them
    bool plain = true;                 ///< run plain traversal
    bool robust = true;                ///< run robust traversal
    bool brute = true;                 ///< include the brute-force structure
    bool split_rays = false;           ///< structures: share opt.rays among the scenes
};

/// run_watertight restricted to `sel` (methods, plain/robust, brute).
std::vector<Row> run_watertight(const Options& opt, const Selection& sel);
/// run_adversarial restricted to `sel` (methods, plain/robust, brute).
std::vector<Row> run_adversarial(const Options& opt, const Selection& sel);
/// run_intgrid restricted to `sel` (methods, plain/robust, brute).
std::vector<Row> run_intgrid(const Options& opt, const Selection& sel);
/// run_degenerate restricted to `sel` (plain/robust, brute; the method is always watertight).
std::vector<Row> run_degenerate(const Options& opt, const Selection& sel);
/// run_structures restricted to `sel` (plain/robust, brute, split_rays).
std::vector<Row> run_structures(const Options& opt, const Selection& sel);

/// The leak cases' structures (watertight, intgrid): every registry row by name, then
/// accel_variants().
std::vector<std::string> leak_case_specs();

/// The rays of a leak case for scene k, given a tracer built over it with the subject's
/// structure (so rays may be aimed at the structure's own planes); the same for every method and
/// traversal of one structure.
using LeakRays = std::function<std::vector<Rayf>(std::size_t k, const SceneTracer& tracer)>;

/// The rows of a leak case: every triangle method (float; occlusion-only ones through any-hit) x
/// leak_case_specs() x plain and robust traversal selected by `sel`, each over every scene (one
/// closed mesh each) with rays_for's rays, one thread; a ray that hits nothing is a leak, and a
/// row whose robust traversal lost rays (stability/leak_tally.h) is a defect.
std::vector<Row> leak_rows(std::string_view case_name,
                           const std::vector<Scene>& scenes,
                           const LeakRays& rays_for,
                           const Selection& sel);

/// True when sel runs structure `accel` with traversal `robust`.
bool selected(const Selection& sel, std::string_view accel, bool robust);

/// True when sel runs triangle method `method`.
bool selected_method(const Selection& sel, std::string_view method);

}  // namespace rtlab::stab
