#pragma once
// The thin layer between mesh_io and OpenMesh's readers and writers. Its interface is plain data so
// OpenMesh stays inside openmesh_bridge.cpp; callers validate and triangulate.

#include "intersect/vec.h"
#include "mesh/triangle_mesh.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace rtlab::detail {

/// Polygons exactly as a reader delivered them: positions in file order, faces in file order as
/// vertex-index lists (an index may be out of range or -1 for an invalid handle).
struct RawMesh {
    std::vector<Vec3f> positions;
    std::vector<std::int64_t> face_indices;  ///< all faces' indices, concatenated
    std::vector<std::size_t> face_offsets;   ///< face k is [offsets[k], offsets[k+1]); starts at 0
};

/// Reads a file through OpenMesh's reader for its extension into `out`; false when OpenMesh
/// reports failure. OpenMesh's own log output is silenced during the call.
bool openmesh_read(const std::filesystem::path& path, RawMesh& out);

/// Writes triangles through OpenMesh's writer for the extension of `path` (binary PLY/STL when
/// `binary`), with 9 significant digits in text formats so floats round-trip exactly; false on
/// failure.
bool openmesh_write(const TriangleMesh& mesh, const std::filesystem::path& path, bool binary);

}  // namespace rtlab::detail
