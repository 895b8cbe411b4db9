#pragma once
// Sphere tessellation into closed, vertex-sharing triangle meshes: UV spheres ("uv:UxV") and
// cube-projected spheres ("cube:N"), cone tessellation, plus an edge-based closedness check.

#include "intersect/vec.h"
#include "mesh/triangle_mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::gen {

/// Appends `other` to `out`, offsetting its indices (positions are copied, never merged).
void append_mesh(TriangleMesh& out, const TriangleMesh& other);

/// How a sphere becomes triangles.
struct SphereTess {
    enum class Kind { uv, cube };
    Kind kind = Kind::uv;  ///< uv: latitude-longitude grid; cube: a subdivided cube projected out
    int u = 16;            ///< uv: segments around the axis (>= 3)
    int v = 8;             ///< uv: rings from pole to pole (>= 2)
    int n = 4;             ///< cube: cells per cube edge (>= 1)

    /// Triangles per sphere: uv 2*U*(V-2) + 2*U (quads plus pole fans); cube 12*N^2.
    [[nodiscard]] std::uint64_t triangles() const;
    /// Vertices per sphere: uv U*(V-1) + 2; cube 6*N^2 + 2.
    [[nodiscard]] std::uint64_t vertices() const;
    /// The canonical spelling, e.g. "uv:16x8" or "cube:4".
    [[nodiscard]] std::string to_string() const;
};

/// Parses "uv:UxV" (3 <= U <= 4096, 2 <= V <= 4096) or "cube:N" (1 <= N <= 2048); throws
/// rtlab::Error with a one-line message otherwise.
[[nodiscard]] SphereTess parse_sphere_tess(std::string_view text);

/// Appends one tessellated sphere (closed 2-manifold, shared vertices, outward winding) to out;
/// positions are computed in double and rounded to float once.
void append_sphere(TriangleMesh& out, const Vec3d& center, double radius, const SphereTess& tess);

/// A sphere to tessellate: centre and radius in double precision.
struct SphereSpec {
    Vec3d center;
    double radius = 1;
};

/// Appends many tessellated spheres, building the unit template once.
void append_spheres(TriangleMesh& out, std::span<const SphereSpec> spheres, const SphereTess& tess);

/// Appends one tessellated truncated cone (scene/prim_cone.h): `segments` (>= 3) triangle pairs
/// around the lateral surface (one band: generators are straight, so the mesh's vertices lie on
/// the cone), a single vertex at an end of radius 0, and a triangle fan per requested cap;
/// outward winding. Closed only when both ends are capped or pointed. Computed in double, rounded
/// to float once.
void append_cone(TriangleMesh& out,
                 const Vec3d& base,
                 double base_radius,
                 const Vec3d& apex,
                 double apex_radius,
                 bool cap_base,
                 bool cap_apex,
                 int segments);

/// Appends the surface of the integer box [0,n]^3 split into unit squares (two triangles each):
/// 12*n^2 triangles, 6*n^2 + 2 vertices, all coordinates integers, outward winding.
void append_integer_cube(TriangleMesh& out, int n, const Vec3d& origin);

/// True when every directed edge occurs exactly once and its reverse occurs too, and no triangle
/// repeats a vertex: a closed, consistently oriented 2-manifold surface (edge check only; vertex
/// fans are not checked).
[[nodiscard]] bool is_closed_manifold(const TriangleMesh& mesh);

}  // namespace rtlab::gen
