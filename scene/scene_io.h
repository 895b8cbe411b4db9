#pragma once
// Scene files: JSON (documented in docs/scene-format.md) or a bare mesh file that becomes a scene
// with one mesh, the default material, one light and a camera framing it.

#include "base/error.h"
#include "scene/scene.h"

#include <filesystem>
#include <string_view>

namespace rtlab {

/// Loads a scene: a .nff file (scene/nff_io.h), a .json scene file (mesh `file`s relative to it,
/// loaded through mesh/) or a mesh file (.obj .ply .off .stl). Throws Error "<file>: <json path>:
/// <problem>" on any bad input.
Scene load_scene(const std::filesystem::path& path);

/// Parses scene JSON text; `base_dir` resolves mesh files and `what` names the source in errors.
Scene parse_scene(std::string_view json_text,
                  const std::filesystem::path& base_dir,
                  std::string_view what);

/// Checks the invariants load_scene guarantees (sizes, finite values, material indices, order);
/// throws Error prefixed with `what` and the JSON path of the first bad field.
void validate_scene(const Scene& s, std::string_view what);

/// Writes s as JSON to `path` (temporary file + rename). With write_meshes, every mesh is also
/// written beside it as binary PLY named "<stem>.mesh<i>.ply" and referenced by that name;
/// otherwise meshes are referenced by their `file` field, which must then be non-empty.
void save_scene(const Scene& s, const std::filesystem::path& path, bool write_meshes);

/// A camera that frames `b` from the +z side (looking down -z, y up) at the given fov and size.
Camera camera_framing(const Bounds3f& b, float fov_deg = 45, int width = 512, int height = 512);

}  // namespace rtlab
