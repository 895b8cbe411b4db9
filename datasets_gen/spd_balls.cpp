// SPD "balls" (Haines 1987): the sphere flake on a square floor, and `far`, the same flake moved
// to x = 1e6 so float coordinates keep only a few bits below the sphere radii. O(spheres).
#include "datasets_gen/scene_parts.h"
#include "datasets_gen/sphere_flake.h"

#include <vector>

namespace rtlab::gen {

namespace {

/// The SPD sphere colour and finish: NFF "f 1 0.9 0.7 0.5 0.5 3.0827 0 0" - diffuse 0.5, specular
/// and mirror 0.5, Phong exponent 3.0827, no transmission.
Material flake_sphere_material() {
    return make_material("flake", {1.0f, 0.9f, 0.7f}, 0.5f, 0.5f, 3.0827f, 0.5f);
}

/// The SPD floor: colour (1, 0.75, 0.33), diffuse 0.8, nothing else.
Material flake_floor_material() {
    return make_material("floor", {1.0f, 0.75f, 0.33f}, 0.8f, 0.0f, 1.0f, 0.0f);
}

Scene make_flake_at(const GenOptions& o, const Vec3d& offset) {
    Scene s;
    set_spd_view(s, offset);
    s.materials = {flake_sphere_material(), flake_floor_material()};
    const std::vector<FlakeSphere> flake = sphere_flake(o.size);
    std::vector<SphereSpec> specs;
    specs.reserve(flake.size());
    for (const FlakeSphere& f : flake) {
        specs.push_back({f.center + offset, f.radius});
    }
    add_spheres(s, specs, 0, o);
    add_floor(s, offset.x, offset.y, offset.z - 0.5, 12.0, 1, o.as_mesh);
    return s;
}

GenCounts flake_counts(const GenOptions& o) {
    return with_floor_counts(sphere_counts(flake_sphere_count(o.size), o), o);
}

Scene make_flake(const GenOptions& o) {
    return make_flake_at(o, {0, 0, 0});
}

Scene make_far(const GenOptions& o) {
    return make_flake_at(o, {1e6, 0, 0});
}

}  // namespace

Generator flake_generator() {
    return {
        "flake",
        "SPD sphere flake: spheres with 9 tangent children of 1/3 radius each, on a 24x24 floor",
        "spheres = (9^(SF+1)-1)/8 (SF 4: 7381); mesh: spheres * tess triangles; + 1 floor "
        "polygon (2 triangles as mesh)",
        0,
        4,
        12,
        flake_counts,
        make_flake};
}

Generator far_generator() {
    return {"far",
            "the sphere flake (view, lights and floor too) moved to x = 1e6",
            "as flake: spheres = (9^(SF+1)-1)/8 + 1 floor",
            0,
            3,
            12,
            flake_counts,
            make_far};
}

}  // namespace rtlab::gen
