// Shared generator pieces: random source, SPD view, floor, sphere sets.
#include "datasets_gen/scene_parts.h"

#include "scene/scene_setting.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace rtlab::gen {

double Rng::normal() {
    // 1 - uniform() lies in (0, 1], so the log is finite.
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

Vec3d Rng::direction() {
    for (;;) {
        const Vec3d g{normal(), normal(), normal()};
        const double len = length(g);
        if (len > 1e-12) {
            return g / len;
        }
    }
}

Material make_material(std::string name,
                       const Vec3f& color,
                       float diffuse,
                       float specular,
                       float shininess,
                       float reflect,
                       float transmit,
                       float ior) {
    Material m;
    m.name = std::move(name);
    m.color = color;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    m.reflect = reflect;
    m.transmit = transmit;
    m.ior = ior;
    return m;
}

Camera look_at(const Vec3d& from, const Vec3d& at) {
    Camera c;
    c.from = Vec3f(from);
    c.at = Vec3f(at);
    c.up = {0, 0, 1};
    c.fov_deg = 45;
    return c;
}

void set_spd_view(Scene& s, const Vec3d& offset) {
    s.camera = look_at(Vec3d{2.1, 1.3, 1.7} + offset, offset);
    s.background = {0.078f, 0.361f, 0.753f};
    s.lights.clear();
    for (const Vec3d& p : {Vec3d{4, 3, 2}, Vec3d{1, -4, 4}, Vec3d{-3, 1, 5}}) {
        Light l;
        l.position = Vec3f(p + offset);
        // The SPD rule for renderers that do not scale lights: 1/sqrt(n) each (n = 3).
        const auto k = static_cast<float>(1.0 / std::sqrt(3.0));
        l.color = {k, k, k};
        s.lights.push_back(l);
    }
}

void add_floor(
    Scene& s, double cx, double cy, double z, double half, std::uint32_t material, bool as_mesh) {
    const std::vector<Vec3f> corners{
        Vec3f(Vec3d{cx - half, cy - half, z}), Vec3f(Vec3d{cx + half, cy - half, z}),
        Vec3f(Vec3d{cx + half, cy + half, z}), Vec3f(Vec3d{cx - half, cy + half, z})};
    if (as_mesh) {
        MeshObject m;
        m.mesh.positions = corners;
        m.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
        m.material = material;
        s.add(std::move(m));
    } else {
        s.add(PolygonObject{corners, material, {}});
    }
}

void add_spheres(Scene& s,
                 std::span<const SphereSpec> spheres,
                 std::uint32_t material,
                 const GenOptions& o) {
    if (o.as_mesh) {
        MeshObject m;
        m.mesh.positions.reserve(spheres.size() * o.tess.vertices());
        m.mesh.triangles.reserve(spheres.size() * o.tess.triangles());
        append_spheres(m.mesh, spheres, o.tess);
        m.material = material;
        s.add(std::move(m));
        return;
    }
    s.spheres.reserve(s.spheres.size() + spheres.size());
    s.order.reserve(s.order.size() + spheres.size());
    for (const SphereSpec& sp : spheres) {
        s.add(SphereObject{Vec3f(sp.center), static_cast<float>(sp.radius), material});
    }
}

GenCounts sphere_counts(std::uint64_t n, const GenOptions& o) {
    GenCounts c;
    if (o.as_mesh) {
        c.triangles = saturating_mul(n, o.tess.triangles());
    } else {
        c.spheres = n;
    }
    return c;
}

GenCounts with_floor_counts(GenCounts c, const GenOptions& o) {
    if (o.as_mesh) {
        c.triangles = saturating_add(c.triangles, 2);
    } else {
        c.polygons = saturating_add(c.polygons, 1);
        c.polygon_vertices = saturating_add(c.polygon_vertices, 4);
    }
    return c;
}

Scene scene_as_mesh(const Scene& s, const GenOptions& o) {
    Scene m = setting_of(s);
    m.add(MeshObject{scene_to_mesh(s, o.tess), "", 0});
    return m;
}

}  // namespace rtlab::gen
