#pragma once
// Structural checks of mesh file bytes before OpenMesh sees them. OpenMesh's readers accept
// truncated files, NaN text, short faces and absurd element counts silently (dropping or inventing
// data), so every file is walked here first: counts, sizes, number syntax, finiteness and index
// ranges. Cost: one pass over the bytes.

#include "mesh/mesh_io.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace rtlab::detail {

/// Element counts the file declares (or contains), to compare with what the reader delivered.
struct DeclaredCounts {
    std::size_t vertices = 0;
    std::size_t faces = 0;
    bool vertices_known = true;      ///< false for STL, whose reader welds equal corners
    bool ignored_materials = false;  ///< OBJ: has mtllib/usemtl statements (not used by rtlab)
};

/// Throws Error("<what>: <problem>") when `bytes` is not a well-formed file of format `f` with
/// finite coordinates and in-range face indices of at least 3 vertices; returns the counts.
DeclaredCounts check_mesh_bytes(std::string_view bytes, MeshFormat f, const std::string& what);

/// check_mesh_bytes for PLY (mesh/format_check_ply.cpp).
DeclaredCounts check_ply(std::string_view bytes, const std::string& what);

}  // namespace rtlab::detail
