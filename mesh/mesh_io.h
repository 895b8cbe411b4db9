#pragma once
// Mesh files in and out (OBJ, PLY ASCII/binary, OFF, STL ASCII/binary) through OpenMesh, which
// stays inside mesh/*.cpp. Polygons are fanned from their first vertex, in face order: face k with
// n vertices v0..v(n-1) becomes the n-2 triangles (v0, v(j), v(j+1)) for j = 1..n-2, appended in
// that order right after face k-1's triangles, so triangle order follows the file.

#include "base/error.h"
#include "mesh/triangle_mesh.h"

#include <filesystem>
#include <string_view>

namespace rtlab {

/// Mesh file formats, chosen from the file extension (case-insensitive).
enum class MeshFormat { obj, ply, off, stl };

/// The format of a path's extension (.obj .ply .off .stl); throws Error naming the file otherwise.
MeshFormat mesh_format_of(const std::filesystem::path& path);

/// True when the path has one of the mesh extensions.
bool is_mesh_path(const std::filesystem::path& path);

/// Options for save_mesh.
struct MeshSaveOptions {
    bool binary = true;  ///< PLY and STL: binary (true) or ASCII; OBJ and OFF are always ASCII
};

/// Reads a mesh file. Throws Error ("<file>: <problem>") when the file is missing, has an unknown
/// extension, cannot be parsed, is truncated, has NaN/inf coordinates, a face index out of range,
/// a face with < 3 vertices, or no triangle at all.
TriangleMesh load_mesh(const std::filesystem::path& path);

/// Writes a mesh (format from the extension; OBJ by our own writer with shortest round-trip
/// floats, because OpenMesh's OBJ writer uses fixed-point, the others by OpenMesh) through a
/// temporary file in the same folder that is renamed over `path` on success, so a failure never
/// leaves a half-written file. Every vertex is written, in order; triangles in order. Throws Error
/// on an invalid mesh or an I/O failure.
void save_mesh(const TriangleMesh& mesh,
               const std::filesystem::path& path,
               const MeshSaveOptions& options = {});

/// Checks a mesh is usable: at least one triangle, finite positions, indices in range. Throws
/// Error prefixed with `what` (usually the file name) otherwise.
void validate_mesh(const TriangleMesh& mesh, std::string_view what);

}  // namespace rtlab
