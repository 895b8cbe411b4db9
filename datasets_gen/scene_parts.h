#pragma once
// Pieces shared by the generators: a portable seeded random source, SPD materials and floor, and
// adding spheres either as analytic objects or tessellated into one mesh.

#include "datasets_gen/generators.h"
#include "datasets_gen/memory_guard.h"
#include "datasets_gen/tessellate.h"
#include "scene/scene.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rtlab::gen {

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, portable generator, so a seed gives the same
/// numbers with every compiler and standard library (std distributions are not portable).
class Rng {
public:
    /// Starts the sequence for `seed`.
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    /// Next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /// Uniform double in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }
    /// Uniform double in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Standard normal deviate (Box-Muller, one of the pair).
    double normal();
    /// Uniform point in [lo, hi)^3.
    Vec3d point(double lo, double hi) {
        return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)};
    }
    /// Uniform unit vector (normalised Gaussian triple).
    Vec3d direction();

private:
    std::uint64_t state_;
};

/// A material with the given name, colour and Whitted coefficients (ambient keeps its default).
[[nodiscard]] Material make_material(std::string name,
                                     const Vec3f& color,
                                     float diffuse,
                                     float specular,
                                     float shininess,
                                     float reflect,
                                     float transmit = 0,
                                     float ior = 1);

/// The SPD "balls" view: eye (2.1, 1.3, 1.7) looking at the origin, up +Z, 45 degree fov, three
/// point lights at (4,3,2), (1,-4,4), (-3,1,5) of intensity 1/sqrt(3) each (the SPD rule) and
/// background (0.078, 0.361, 0.753).
void set_spd_view(Scene& s, const Vec3d& offset = {0, 0, 0});

/// A square floor at height z spanning +-half in x and y around (cx, cy): a polygon object, or a
/// two-triangle mesh object when as_mesh.
void add_floor(
    Scene& s, double cx, double cy, double z, double half, std::uint32_t material, bool as_mesh);

/// Adds spheres with one material: analytic sphere objects, or one mesh object of tessellated
/// spheres when o.as_mesh.
void add_spheres(Scene& s,
                 std::span<const SphereSpec> spheres,
                 std::uint32_t material,
                 const GenOptions& o);

/// Counts of add_spheres(n spheres) under o.
[[nodiscard]] GenCounts sphere_counts(std::uint64_t n, const GenOptions& o);

/// c plus the counts of one add_floor under o.
[[nodiscard]] GenCounts with_floor_counts(GenCounts c, const GenOptions& o);

/// s's setting (camera, background, lights, materials) with everything in it as one mesh object
/// of material 0 (scene_to_mesh with o.tess).
[[nodiscard]] Scene scene_as_mesh(const Scene& s, const GenOptions& o);

/// A camera looking from `from` at `at`, up +Z, 45 degree fov.
[[nodiscard]] Camera look_at(const Vec3d& from, const Vec3d& at);

// Generator rows, one per file (spd_*.cpp, stress_*.cpp).
std::vector<Generator> spd_generators();  ///< the exact SPD databases (spd_databases.h)
Generator flake_generator();
Generator terrain_generator();
Generator spiral_generator();
Generator gearbox_generator();
Generator soup_generator();
Generator soup_clustered_generator();
Generator stadium_generator();
Generator slivers_generator();
Generator intgrid_generator();
Generator far_generator();
Generator scales_generator();
Generator coplanar_generator();
Generator nested_generator();

}  // namespace rtlab::gen
