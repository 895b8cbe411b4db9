#pragma once
// Mesh statistics: counts, bounds, degenerate and duplicate faces, boundary and non-manifold edges.
// Edges are undirected vertex-index pairs (positions are not welded). Cost: O(F log F).

#include "intersect/bounds.h"
#include "mesh/triangle_mesh.h"

#include <cstddef>

namespace rtlab {

/// What mesh_stats reports.
struct MeshStats {
    std::size_t vertices = 0;  ///< positions, referenced or not
    std::size_t unreferenced_vertices = 0;
    std::size_t triangles = 0;
    Bounds3f bounds;                       ///< of the triangles
    std::size_t degenerate_triangles = 0;  ///< zero area (cross product exactly 0) or non-finite
    std::size_t duplicate_triangles = 0;   ///< same vertex set as an earlier triangle, any order
    std::size_t edges = 0;                 ///< distinct undirected edges
    std::size_t boundary_edges = 0;        ///< used by exactly one triangle
    std::size_t non_manifold_edges = 0;    ///< used by three or more triangles
    std::size_t inconsistent_edges = 0;    ///< two triangles traversing the edge the same way
    /// True for a closed, consistently oriented 2-manifold: every edge shared by exactly two
    /// triangles that traverse it in opposite directions, at least one triangle, and no triangle
    /// repeating a vertex index.
    bool closed = false;
    friend bool operator==(const MeshStats&, const MeshStats&) = default;
};

/// Statistics of m (indices must be in range, as load_mesh guarantees).
MeshStats mesh_stats(const TriangleMesh& m);

}  // namespace rtlab
