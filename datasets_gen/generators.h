#pragma once
// The generator registry behind `rtlab gen`: every procedural scene (SPD family and stress
// scenes) as one row {name, description, count formula, counts, make}. A new generator is one
// function plus one row in generators.cpp.

#include "datasets_gen/tessellate.h"
#include "mesh/triangle_mesh.h"
#include "scene/scene.h"

#include <cstdint>
#include <span>
#include <string_view>

namespace rtlab::gen {

/// What to generate. The same options (and seed) always give the same scene, bit for bit.
struct GenOptions {
    int size = -1;                   ///< size factor SF; -1 picks the generator's default
    bool as_mesh = false;            ///< tessellate analytic spheres into one mesh object
    SphereTess tess;                 ///< how spheres are tessellated (default uv:16x8)
    std::uint64_t seed = 1;          ///< seeds random generators; ignored by deterministic ones
    std::uint64_t memory_limit = 0;  ///< bytes; 0 means default_memory_limit()
};

/// Primitives a generated scene holds (with the options it was asked for).
struct GenCounts {
    std::uint64_t spheres = 0;           ///< analytic spheres
    std::uint64_t triangles = 0;         ///< mesh triangles over all mesh objects
    std::uint64_t polygons = 0;          ///< polygon objects
    std::uint64_t polygon_vertices = 0;  ///< vertices over all polygons
    std::uint64_t cones = 0;             ///< truncated cones and cylinders
    friend bool operator==(const GenCounts&, const GenCounts&) = default;
};

/// One procedural scene generator.
struct Generator {
    std::string_view name;           ///< command-line name, e.g. "flake"
    std::string_view description;    ///< one line
    std::string_view count_formula;  ///< primitive count as a function of SF, for --list and docs
    int min_size = 0;                ///< smallest accepted SF
    int default_size = 0;            ///< SF used when none is given
    int max_size = 0;                ///< largest accepted SF (the memory guard may refuse earlier)
    GenCounts (*counts)(const GenOptions& o);  ///< exact counts for o.size (already resolved)
    Scene (*make)(const GenOptions& o);        ///< builds the scene for o.size (already resolved)
};

/// Every generator, in --list order.
[[nodiscard]] std::span<const Generator> generators();

/// The generator called `name`, or nullptr.
[[nodiscard]] const Generator* find_generator(std::string_view name);

/// Estimated peak bytes of generating and saving a scene with these counts (saving as JSON
/// dominates): 1 KiB per analytic sphere or cone, 64 B per triangle, 256 B per polygon plus 96 B
/// per polygon vertex.
[[nodiscard]] std::uint64_t estimate_bytes(const GenCounts& c);

/// Generates a scene: resolves the default size, refuses sizes outside [min_size, max_size] and
/// estimates over the memory limit (rtlab::Error, one line, the estimate in the message).
/// With as_mesh, cones become tess.u triangle pairs around (scene_to_mesh).
[[nodiscard]] Scene generate(const Generator& g, GenOptions o);

/// Generates by name; throws rtlab::Error listing the names when there is no such generator.
[[nodiscard]] Scene generate(std::string_view name, const GenOptions& o);

/// One mesh of everything in s: meshes copied, spheres tessellated with `tess`, cones with tess.u
/// segments around (append_cone), polygons fanned from their vertex average (correct for
/// polygons star-shaped about it, as all generated ones are). Throws rtlab::Error for boxes,
/// oriented boxes and implicit surfaces.
[[nodiscard]] TriangleMesh scene_to_mesh(const Scene& s, const SphereTess& tess);

}  // namespace rtlab::gen
