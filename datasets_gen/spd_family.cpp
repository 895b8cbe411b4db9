// Stress scenes in the spirit of the SPD family (not the SPD databases themselves, which are in
// spd_databases.cpp): `terrain`, a seeded diamond-square fractal with glass spheres; `spiral`, a
// Pickover-style shell of overlapping spheres; `gearbox`, gears of large concave polygons.
#include "datasets_gen/scene_parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace rtlab::gen {

namespace {

/// Eye on the SPD view direction (2.1, 1.3, 1.7) at `distance` from `at`; SPD lights and
/// background.
void set_view_around(Scene& s, const Vec3d& at, double distance) {
    set_spd_view(s);
    s.camera = look_at(at + normalize(Vec3d{2.1, 1.3, 1.7}) * distance, at);
}

// ---- terrain: (2^SF+1)^2 height samples by diamond-square midpoint displacement (Fournier,
// Fussell & Carpenter 1982) over [-1,1]^2, amplitude halved per level; triangles = 2 * 4^SF, plus 4
// glass spheres floating above it.

std::vector<double> diamond_square(int n, Rng& rng) {
    const auto side = static_cast<std::size_t>(n) + 1;
    std::vector<double> h(side * side, 0.0);
    const auto at = [&](int x, int y) -> double& {
        return h[static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)];
    };
    double amp = 0.4;
    for (int step = n; step > 1; step /= 2) {
        const int half = step / 2;
        for (int y = half; y < n; y += step) {
            for (int x = half; x < n; x += step) {
                at(x, y) = 0.25 * (at(x - half, y - half) + at(x + half, y - half) +
                                   at(x - half, y + half) + at(x + half, y + half)) +
                           rng.uniform(-amp, amp);
            }
        }
        for (int y = 0; y <= n; y += half) {
            for (int x = (y / half) % 2 == 0 ? half : 0; x <= n; x += step) {
                double sum = 0;
                int count = 0;
                const int dx[4] = {-half, half, 0, 0};
                const int dy[4] = {0, 0, -half, half};
                for (int k = 0; k < 4; ++k) {
                    const int xx = x + dx[k];
                    const int yy = y + dy[k];
                    if (xx >= 0 && xx <= n && yy >= 0 && yy <= n) {
                        sum += at(xx, yy);
                        ++count;
                    }
                }
                at(x, y) = sum / count + rng.uniform(-amp, amp);
            }
        }
        amp *= 0.5;
    }
    return h;
}

GenCounts mount_counts(const GenOptions& o) {
    GenCounts c = sphere_counts(4, o);
    c.triangles = saturating_add(c.triangles, saturating_mul(2, saturating_pow(4, o.size)));
    return c;
}

Scene make_mount(const GenOptions& o) {
    Scene s;
    set_view_around(s, {0, 0, 0}, 3.2);
    s.materials = {make_material("mountain", {1.0f, 0.5f, 0.45f}, 0.8f, 0.0f, 1.0f, 0.0f),
                   make_material("glass", {1.0f, 1.0f, 1.0f}, 0.0f, 0.5f, 30.0f, 0.1f, 0.9f, 1.5f)};
    Rng rng(o.seed);
    const int n = 1 << o.size;
    const std::vector<double> h = diamond_square(n, rng);
    MeshObject obj;
    const auto side = static_cast<std::uint32_t>(n + 1);
    for (std::uint32_t y = 0; y < side; ++y) {
        for (std::uint32_t x = 0; x < side; ++x) {
            obj.mesh.positions.push_back(
                Vec3f(Vec3d{2.0 * x / n - 1.0, 2.0 * y / n - 1.0, h[y * side + x]}));
        }
    }
    for (std::uint32_t y = 0; y + 1 < side; ++y) {
        for (std::uint32_t x = 0; x + 1 < side; ++x) {
            const std::uint32_t v = y * side + x;
            obj.mesh.triangles.push_back({v, v + 1, v + side + 1});
            obj.mesh.triangles.push_back({v, v + side + 1, v + side});
        }
    }
    s.add(std::move(obj));
    const double top = *std::max_element(h.begin(), h.end());
    const double r = 0.15;
    std::vector<SphereSpec> glass;
    for (const auto& [x, y] : {std::pair{-0.45, -0.45}, std::pair{0.45, -0.45},
                               std::pair{0.45, 0.45}, std::pair{-0.45, 0.45}}) {
        glass.push_back({{x, y, top + r}, r});
    }
    add_spheres(s, glass, 1, o);
    return s;
}

// ---- spiral: N = 2^(SF+7) overlapping spheres along a logarithmic helico-spiral (after Pickover's
// seashells): radius and distance from the axis grow as e^(k*theta), height drops with them.

GenCounts shells_counts(const GenOptions& o) {
    return sphere_counts(saturating_pow(2, o.size + 7), o);
}

Scene make_shells(const GenOptions& o) {
    Scene s;
    set_view_around(s, {0, 0, -0.3}, 3.5);
    s.materials = {make_material("shell", {1.0f, 0.8f, 0.6f}, 0.7f, 0.3f, 20.0f, 0.2f),
                   make_material("floor", {0.6f, 0.6f, 0.65f}, 0.8f, 0.0f, 1.0f, 0.0f)};
    const std::uint64_t count = saturating_pow(2, o.size + 7);
    const double turns = 5.0;
    const double theta_max = 2 * std::numbers::pi * turns;
    const double k = std::log(50.0) / theta_max;  // radius grows 50-fold over the whole shell
    const double r_max = 0.35;
    std::vector<SphereSpec> spheres;
    spheres.reserve(count);
    for (std::uint64_t i = 0; i < count; ++i) {
        const double theta = theta_max * static_cast<double>(i) / static_cast<double>(count);
        const double r = r_max * std::exp(k * (theta - theta_max));
        const double d = 1.4 * r;
        spheres.push_back({{d * std::cos(theta), d * std::sin(theta), 0.4 - 2.2 * r}, r});
    }
    add_spheres(s, spheres, 0, o);
    add_floor(s, 0, 0, -1.0, 6.0, 1, o.as_mesh);
    return s;
}

// ---- gearbox: a 2^SF x 2^SF grid of gears with T = 16 teeth; each gear is a concave top and
// bottom polygon of 4T vertices plus 4T side quads: polygons = 4^SF * (2 + 4T) + 1 floor.
// As a mesh every polygon is fanned from its vertex average: 4^SF * 24T + 4 triangles.

constexpr int gear_teeth = 16;

GenCounts gears_counts(const GenOptions& o) {
    const std::uint64_t gears = saturating_pow(4, o.size);
    GenCounts c;
    if (o.as_mesh) {
        c.triangles = saturating_add(saturating_mul(gears, 24 * gear_teeth), 4);
    } else {
        c.polygons = saturating_add(saturating_mul(gears, 2 + 4 * gear_teeth), 1);
        c.polygon_vertices = saturating_add(saturating_mul(gears, 24 * gear_teeth), 4);
    }
    return c;
}

void add_gear(Scene& s, double cx, double cy, double phase, std::uint32_t material) {
    const double outer = 1.0;
    const double inner = 0.8;
    const double height = 0.25;
    const int n = 4 * gear_teeth;
    std::vector<Vec3d> outline;  // counter-clockwise seen from +Z
    for (int t = 0; t < gear_teeth; ++t) {
        const double a0 = 2 * std::numbers::pi * t / gear_teeth + phase;
        const double step = 2 * std::numbers::pi / gear_teeth / 4;
        outline.push_back({cx + inner * std::cos(a0), cy + inner * std::sin(a0), 0});
        outline.push_back({cx + outer * std::cos(a0 + step), cy + outer * std::sin(a0 + step), 0});
        outline.push_back(
            {cx + outer * std::cos(a0 + 2 * step), cy + outer * std::sin(a0 + 2 * step), 0});
        outline.push_back(
            {cx + inner * std::cos(a0 + 3 * step), cy + inner * std::sin(a0 + 3 * step), 0});
    }
    const Vec3d up{0, 0, height};
    PolygonObject top{{}, material, {}};
    PolygonObject bottom{{}, material, {}};
    for (int i = 0; i < n; ++i) {
        top.vertices.push_back(Vec3f(outline[static_cast<std::size_t>(i)] + up));
        bottom.vertices.push_back(Vec3f(outline[static_cast<std::size_t>(n - 1 - i)]));
    }
    s.add(std::move(top));
    s.add(std::move(bottom));
    for (int i = 0; i < n; ++i) {
        const Vec3d& a = outline[static_cast<std::size_t>(i)];
        const Vec3d& b = outline[static_cast<std::size_t>((i + 1) % n)];
        s.add(PolygonObject{{Vec3f(a), Vec3f(b), Vec3f(b + up), Vec3f(a + up)}, material, {}});
    }
}

Scene make_gears(const GenOptions& o) {
    Scene s;
    const int n = 1 << o.size;
    const double pitch = 1.9;  // teeth of neighbours interleave
    const double extent = pitch * (n - 1);
    set_view_around(s, {extent / 2, extent / 2, 0}, 2.5 + 1.6 * pitch * n);
    s.materials = {make_material("gear", {0.8f, 0.8f, 0.9f}, 0.6f, 0.4f, 40.0f, 0.3f),
                   make_material("floor", {0.3f, 0.5f, 0.3f}, 0.8f, 0.0f, 1.0f, 0.0f)};
    const double half_tooth = std::numbers::pi / gear_teeth;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            add_gear(s, pitch * x, pitch * y, (x + y) % 2 == 0 ? 0.0 : half_tooth, 0);
        }
    }
    add_floor(s, extent / 2, extent / 2, -0.01, extent / 2 + 2, 1, false);
    if (o.as_mesh) {
        return scene_as_mesh(s, o);
    }
    return s;
}

}  // namespace

Generator terrain_generator() {
    return {"terrain",
            "diamond-square fractal terrain (seeded) with 4 glass spheres",
            "triangles = 2*4^SF (SF 6: 8192) + 4 spheres (4 * tess triangles as mesh)",
            0,
            6,
            14,
            mount_counts,
            make_mount};
}

Generator spiral_generator() {
    return {
        "spiral",
        "Pickover-style seashell: overlapping spheres on a logarithmic helico-spiral, on a floor",
        "spheres = 2^(SF+7) (SF 4: 2048) + 1 floor polygon (2 triangles as mesh)",
        0,
        4,
        24,
        [](const GenOptions& o) { return with_floor_counts(shells_counts(o), o); },
        make_shells};
}

Generator gearbox_generator() {
    return {
        "gearbox",
        "grid of 16-tooth gears: large concave polygons (top/bottom) plus side quads, on a floor",
        "polygons = 4^SF*66 + 1 (vertices 4^SF*384 + 4); mesh: triangles = 4^SF*384 + 4",
        0,
        2,
        10,
        gears_counts,
        make_gears};
}

}  // namespace rtlab::gen
