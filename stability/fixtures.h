#pragma once
// Scenes and ray sets of the stability cases that `rtlab stability --fixture` also writes to
// files, so `rtlab trace` can be checked on exactly the rays the suite traces; and the case entry
// points with a subject selection, so the fast tests run only the subjects whose property they
// assert while the report runs the whole matrix.

#include "intersect/ray.h"
#include "mesh/triangle_mesh.h"
#include "scene/scene.h"
#include "stability/stability.h"

#include <cstddef>
#include <cstdint>
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

/// Which subjects a case runs; the default is the whole matrix (what the report shows).
struct Selection {
    std::vector<std::string> methods;  ///< triangle method names; empty means every method
    bool plain = true;                 ///< run plain traversal
    bool robust = true;                ///< run robust traversal
    bool brute = true;                 ///< include the brute-force structure
    bool split_rays = false;           ///< structures: share opt.rays among the scenes
};

/// run_watertight restricted to `sel` (methods, plain/robust, brute).
std::vector<Row> run_watertight(const Options& opt, const Selection& sel);
/// run_intgrid restricted to `sel` (methods, plain/robust, brute).
std::vector<Row> run_intgrid(const Options& opt, const Selection& sel);
/// run_degenerate restricted to `sel` (plain/robust, brute; the method is always watertight).
std::vector<Row> run_degenerate(const Options& opt, const Selection& sel);
/// run_structures restricted to `sel` (plain/robust, brute, split_rays).
std::vector<Row> run_structures(const Options& opt, const Selection& sel);

/// The leak cases' structures (watertight, intgrid): every registry row by name, then
/// accel_variants().
std::vector<std::string> leak_case_specs();

/// The rows of a leak case: every triangle method (float; occlusion-only ones through any-hit) x
/// leak_case_specs() x plain and robust traversal selected by `sel`, over `scene`'s one mesh,
/// one thread; a ray of `rays` that hits nothing is a leak.
std::vector<Row> leak_rows(std::string_view case_name,
                           const Scene& scene,
                           const std::vector<Rayf>& rays,
                           const Selection& sel);

/// True when sel runs structure `accel` with traversal `robust`.
bool selected(const Selection& sel, std::string_view accel, bool robust);

/// True when sel runs triangle method `method`.
bool selected_method(const Selection& sel, std::string_view method);

}  // namespace rtlab::stab
