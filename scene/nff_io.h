#pragma once
// Neutral File Format (NFF, Haines' SPD, 1987): the records as a document (read and written
// record for record, so cones and patch normals survive a round trip), and conversion to and from
// a Scene. The records: `v` (view), `b` (background), `l` (light), `f` (fill), `s` (sphere), `c`
// (truncated cone, open ends), `p` (polygon), `pp` (polygonal patch with vertex normals); `#`
// starts a comment line.

#include "intersect/vec.h"
#include "scene/scene.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rtlab::nff {

/// `v` with from/at/up/angle/hither/resolution.
struct View {
    Vec3d from;
    Vec3d at;
    Vec3d up{0, 0, 1};
    double angle = 45;  ///< vertical field of view, degrees
    double hither = 0;  ///< nearest hit distance
    int width = 512;
    int height = 512;
    friend bool operator==(const View&, const View&) = default;
};

/// `b r g b`.
struct Background {
    Vec3d color;
    friend bool operator==(const Background&, const Background&) = default;
};

/// `l x y z [r g b]`; NFF lights carry no intensity (see to_scene).
struct Light {
    Vec3d position;
    bool has_color = false;
    Vec3d color{1, 1, 1};
    friend bool operator==(const Light&, const Light&) = default;
};

/// `f r g b Kd Ks Shine T index_of_refraction`: the material of the primitives after it.
struct Fill {
    Vec3d color{1, 1, 1};
    double kd = 1;
    double ks = 0;
    double shine = 1;
    double t = 0;
    double ior = 1;
    friend bool operator==(const Fill&, const Fill&) = default;
};

/// `s x y z r`.
struct Sphere {
    Vec3d center;
    double radius = 0;
    friend bool operator==(const Sphere&, const Sphere&) = default;
};

/// `c` base, base radius, apex, apex radius: a truncated cone open at both ends.
struct Cone {
    Vec3d base;
    double base_radius = 0;
    Vec3d apex;
    double apex_radius = 0;
    friend bool operator==(const Cone&, const Cone&) = default;
};

/// `p n` (normals empty) or `pp n` (one normal per vertex); one-sided, winding order matters.
struct Polygon {
    std::vector<Vec3d> vertices;
    std::vector<Vec3d> normals;
    friend bool operator==(const Polygon&, const Polygon&) = default;
};

/// One NFF record.
using Record = std::variant<View, Background, Light, Fill, Sphere, Cone, Polygon>;

/// A whole NFF file, records in file order.
struct Document {
    std::vector<Record> records;
    friend bool operator==(const Document&, const Document&) = default;
};

/// Primitive counts of a document.
struct Counts {
    std::size_t spheres = 0;
    std::size_t cones = 0;
    std::size_t polygons = 0;  ///< `p` records
    std::size_t patches = 0;   ///< `pp` records
    std::size_t lights = 0;
    std::size_t vertices = 0;  ///< over all `p` and `pp` records
};

/// Counts the primitives and lights of d.
[[nodiscard]] Counts count(const Document& d);

/// Parses NFF text; throws rtlab::Error "<what>:<line>: <problem>" on bad input.
[[nodiscard]] Document parse(std::string_view text, std::string_view what);

/// Reads and parses an NFF file (errors name the file and line).
[[nodiscard]] Document load(const std::filesystem::path& path);

/// The NFF text of d: numbers as C's %g (6 significant digits), as the SPD programs print them.
[[nodiscard]] std::string write(const Document& d);

/// Writes d to path completely or not at all.
void save(const Document& d, const std::filesystem::path& path);

/// The scene of d: view -> camera (resolution, angle), background, lights with intensity
/// 1/sqrt(n) each for n lights without colour (the SPD rule for renderers that do not scale),
/// fills -> materials (Kd diffuse, Ks specular and mirror weight, Shine Phong exponent, T
/// transmission, index of refraction at least 1), spheres, cones (open: no caps) and polygons in
/// order (`pp` normals become the polygon's vertex normals). Throws rtlab::Error naming `what` when
/// the document has no view or no primitive.
[[nodiscard]] Scene to_scene(const Document& d, std::string_view what);

/// The NFF document of s: view, background, lights (colour written when not 1/sqrt(n) grey), one
/// fill before each run of objects sharing a material, spheres, open cones, polygons (`pp` with
/// vertex normals) and mesh triangles as `p 3`. Throws rtlab::Error for boxes, oriented boxes,
/// implicit surfaces and capped cones (NFF has none).
[[nodiscard]] Document from_scene(const Scene& s);

/// Loads an .nff file as a scene (to_scene).
[[nodiscard]] Scene load_scene_nff(const std::filesystem::path& path);

}  // namespace rtlab::nff
