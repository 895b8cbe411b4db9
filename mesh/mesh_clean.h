#pragma once
// Mesh cleaning: drops triangles with non-finite corners or zero area, then vertices no triangle
// uses. Triangle and vertex order is otherwise kept. Cost: O(V + F).

#include "mesh/triangle_mesh.h"

#include <cstddef>

namespace rtlab {

/// How many elements clean_mesh removed.
struct CleanReport {
    std::size_t non_finite_triangles = 0;  ///< a corner with a NaN or infinite coordinate
    std::size_t degenerate_triangles = 0;  ///< zero area: (p1 - p0) x (p2 - p0) is exactly 0
    std::size_t unreferenced_vertices = 0;
    /// Total triangles removed.
    std::size_t triangles_removed() const { return non_finite_triangles + degenerate_triangles; }
};

/// Removes bad triangles and then unused vertices from m in place, keeping the order of what
/// stays; returns the counts. Indices must be in range.
CleanReport clean_mesh(TriangleMesh& m);

}  // namespace rtlab
