#pragma once
// TriangleMesh: plain-data indexed triangles (no OpenMesh). Triangle i is global to the mesh and
// keeps the order of the file it came from (see mesh_io.h for how polygons are fanned).

#include "intersect/bounds.h"
#include "intersect/vec.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtlab {

/// Indexed triangle mesh: positions plus one index triple per triangle (counter-clockwise seen from
/// the front). Indices must be < positions.size(); mesh_io and validate() enforce it.
struct TriangleMesh {
    std::vector<Vec3f> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;

    /// Number of triangles.
    std::size_t triangle_count() const { return triangles.size(); }
    /// Number of vertices (referenced or not).
    std::size_t vertex_count() const { return positions.size(); }
    /// True when the mesh has no triangle.
    bool empty() const { return triangles.empty(); }
    /// The three corners of triangle i (i < triangle_count()).
    std::array<Vec3f, 3> corners(std::size_t i) const {
        const auto& t = triangles[i];
        return {positions[t[0]], positions[t[1]], positions[t[2]]};
    }
    /// Smallest box around triangle i (i < triangle_count()).
    Bounds3f triangle_bounds(std::size_t i) const {
        const auto& t = triangles[i];
        return Bounds3f(positions[t[0]]).extend(positions[t[1]]).extend(positions[t[2]]);
    }
    /// Smallest box around every triangle (unreferenced vertices are ignored); empty box when the
    /// mesh has no triangle.
    Bounds3f bounds() const {
        Bounds3f b;
        for (const auto& t : triangles) {
            b.extend(positions[t[0]]).extend(positions[t[1]]).extend(positions[t[2]]);
        }
        return b;
    }
    /// One box per triangle, in triangle order (what an acceleration structure is built from).
    std::vector<Bounds3f> all_triangle_bounds() const {
        std::vector<Bounds3f> out;
        out.reserve(triangles.size());
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            out.push_back(triangle_bounds(i));
        }
        return out;
    }
    friend bool operator==(const TriangleMesh&, const TriangleMesh&) = default;
};

}  // namespace rtlab
