// Stress scenes for acceleration structures and intersectors: random soups (uniform, clustered),
// teapot-in-a-stadium, needle slivers, integer-lattice mesh, extreme scales, coplanar overlaps and
// concentric spheres. All O(primitives) and deterministic for (size, seed).
#include "datasets_gen/scene_parts.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace rtlab::gen {

namespace {

/// Camera on the SPD view direction looking at `at` from `distance`, SPD lights (scaled by
/// distance around `at`), plain grey material.
void set_stress_view(Scene& s, const Vec3d& at, double distance) {
    set_spd_view(s);
    s.camera = look_at(at + normalize(Vec3d{2.1, 1.3, 1.7}) * distance, at);
    for (Light& l : s.lights) {
        l.position = Vec3f(at + Vec3d(l.position) * distance);
    }
    s.materials = {make_material("stress", {0.8f, 0.8f, 0.8f}, 0.9f, 0.0f, 1.0f, 0.0f)};
}

std::uint64_t soup_count(int sf) {
    return saturating_mul(1024, saturating_pow(2, sf));
}

GenCounts triangle_counts(std::uint64_t n) {
    GenCounts c;
    c.triangles = n;
    return c;
}

/// Appends an unshared triangle.
void push_triangle(TriangleMesh& m, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back(Vec3f(a));
    m.positions.push_back(Vec3f(b));
    m.positions.push_back(Vec3f(c));
    m.triangles.push_back({base, base + 1, base + 2});
}

Scene one_mesh_scene(TriangleMesh mesh, const Vec3d& at, double distance) {
    Scene s;
    set_stress_view(s, at, distance);
    s.add(MeshObject{std::move(mesh), "", 0});
    return s;
}

// ---- soup: N = 1024 * 2^SF triangles, centres uniform in [0,1]^3, corners uniform within
// +-N^(-1/3) of the centre (so triangles are about as large as their spacing).
Scene make_soup(const GenOptions& o) {
    const std::uint64_t n = soup_count(o.size);
    const double extent = 1.0 / std::cbrt(static_cast<double>(n));
    Rng rng(o.seed);
    TriangleMesh m;
    m.positions.reserve(3 * n);
    m.triangles.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        const Vec3d c = rng.point(0, 1);
        const Vec3d a = c + rng.point(-extent, extent);
        const Vec3d b = c + rng.point(-extent, extent);
        push_triangle(m, a, b, c + rng.point(-extent, extent));
    }
    return one_mesh_scene(std::move(m), {0.5, 0.5, 0.5}, 2.5);
}

// ---- soup_clustered: N = 1024 * 2^SF triangles around 16 cluster centres (uniform in [0,1]^3),
// centres Gaussian with sigma 0.03, corners within +-0.2 * N^(-1/3): dense clumps, empty space.
Scene make_soup_clustered(const GenOptions& o) {
    const std::uint64_t n = soup_count(o.size);
    const double extent = 0.2 / std::cbrt(static_cast<double>(n));
    Rng rng(o.seed);
    std::vector<Vec3d> clusters;
    for (int i = 0; i < 16; ++i) {
        clusters.push_back(rng.point(0, 1));
    }
    TriangleMesh m;
    m.positions.reserve(3 * n);
    m.triangles.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        const Vec3d& k = clusters[rng.next() % clusters.size()];
        const Vec3d c = k + Vec3d{rng.normal(), rng.normal(), rng.normal()} * 0.03;
        const Vec3d a = c + rng.point(-extent, extent);
        const Vec3d b = c + rng.point(-extent, extent);
        push_triangle(m, a, b, c + rng.point(-extent, extent));
    }
    return one_mesh_scene(std::move(m), {0.5, 0.5, 0.5}, 2.5);
}

// ---- stadium: a cube:2^SF sphere of radius 0.01 at the origin (12 * 4^SF triangles) inside the
// inward-facing box [-1000, 1000]^3 (12 triangles): triangles = 12 * 4^SF + 12.
GenCounts stadium_counts(const GenOptions& o) {
    return triangle_counts(saturating_add(saturating_mul(12, saturating_pow(4, o.size)), 12));
}

Scene make_stadium(const GenOptions& o) {
    TriangleMesh m;
    SphereTess tess;
    tess.kind = SphereTess::Kind::cube;
    tess.n = 1 << o.size;
    append_sphere(m, {0, 0, 0}, 0.01, tess);
    TriangleMesh box;
    append_integer_cube(box, 1, {-0.5, -0.5, -0.5});
    for (Vec3f& p : box.positions) {
        p = p * 2000.0f;
    }
    for (auto& t : box.triangles) {
        std::swap(t[1], t[2]);  // face inwards: the camera is inside
    }
    append_mesh(m, box);
    return one_mesh_scene(std::move(m), {0, 0, 0}, 0.05);
}

// ---- slivers: N = 1024 * 2^SF needles of length 0.2 and width 0.2 / 10^(6u), u uniform in
// [0,1]: aspect ratios from 1 to 1e6, centres uniform in [0,1]^3, directions uniform.
Scene make_slivers(const GenOptions& o) {
    const std::uint64_t n = soup_count(o.size);
    Rng rng(o.seed);
    TriangleMesh m;
    m.positions.reserve(3 * n);
    m.triangles.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        const Vec3d c = rng.point(0, 1);
        const Vec3d d = rng.direction();
        Vec3d u;
        Vec3d v;
        const Vec3d helper = std::abs(d.y) > 0.9 ? Vec3d{0, 0, 1} : Vec3d{0, 1, 0};
        u = normalize(cross(helper, d));
        v = cross(d, u);
        const double length_ = 0.2;
        const double width = length_ / std::pow(10.0, 6.0 * rng.uniform());
        const double angle = rng.uniform(0, 2 * std::numbers::pi);
        const Vec3d side = (u * std::cos(angle) + v * std::sin(angle)) * width;
        push_triangle(m, c - d * (length_ / 2), c + d * (length_ / 2), c + side);
    }
    return one_mesh_scene(std::move(m), {0.5, 0.5, 0.5}, 2.5);
}

// ---- intgrid: the surface of the integer cube [-n/2, n/2]^3 (n = 2^SF; [0,1]^3 for SF 0) split
// into unit squares: 12 * 4^SF triangles on 6 * 4^SF + 2 shared integer vertices, closed.
GenCounts intgrid_counts(const GenOptions& o) {
    return triangle_counts(saturating_mul(12, saturating_pow(4, o.size)));
}

Scene make_intgrid(const GenOptions& o) {
    const int n = 1 << o.size;
    const double lo = -static_cast<double>(n / 2);
    TriangleMesh m;
    append_integer_cube(m, n, {lo, lo, lo});
    return one_mesh_scene(std::move(m), {lo + n / 2.0, lo + n / 2.0, lo + n / 2.0}, 2.0 * n + 1);
}

// ---- scales: 13 decades k = -6..6, 2^SF spheres of radius 10^k per decade; sphere j of decade k
// sits at distance 10^k * (4 + 3j) from the origin in azimuth 2 pi (k+6)/13: spheres = 13 * 2^SF.
GenCounts scales_counts(const GenOptions& o) {
    return sphere_counts(saturating_mul(13, saturating_pow(2, o.size)), o);
}

Scene make_scales(const GenOptions& o) {
    Scene s;
    set_stress_view(s, {0, 0, 0}, 1e-4);
    const std::uint64_t per = saturating_pow(2, o.size);
    std::vector<SphereSpec> spheres;
    for (int k = -6; k <= 6; ++k) {
        const double r = std::pow(10.0, k);
        const double az = 2 * std::numbers::pi * (k + 6) / 13.0;
        const Vec3d dir{std::cos(az), std::sin(az), 0};
        for (std::uint64_t j = 0; j < per; ++j) {
            spheres.push_back({dir * (r * (4.0 + 3.0 * static_cast<double>(j))), r});
        }
    }
    add_spheres(s, spheres, 0, o);
    return s;
}

// ---- coplanar: N = 1024 * 2^SF triangles in the plane z = 0, corners uniform in [0,1]^2 around
// centres, size about 0.1 (heavy overlap); every 8th triangle repeats the previous one exactly.
Scene make_coplanar(const GenOptions& o) {
    const std::uint64_t n = soup_count(o.size);
    Rng rng(o.seed);
    TriangleMesh m;
    m.positions.reserve(3 * n);
    m.triangles.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        if (i % 8 == 7) {
            const std::array<Vec3f, 3> prev = m.corners(m.triangles.size() - 1);
            push_triangle(m, Vec3d(prev[0]), Vec3d(prev[1]), Vec3d(prev[2]));
            continue;
        }
        const double cx = rng.uniform(0, 1);
        const double cy = rng.uniform(0, 1);
        Vec3d p[3];
        for (Vec3d& q : p) {
            q = {cx + rng.uniform(-0.05, 0.05), cy + rng.uniform(-0.05, 0.05), 0};
        }
        push_triangle(m, p[0], p[1], p[2]);
    }
    return one_mesh_scene(std::move(m), {0.5, 0.5, 0}, 2.0);
}

// ---- nested: N = 8 * 2^SF concentric spheres at the origin with radii (i+1)/N, i = 0..N-1.
GenCounts nested_counts(const GenOptions& o) {
    return sphere_counts(saturating_mul(8, saturating_pow(2, o.size)), o);
}

Scene make_nested(const GenOptions& o) {
    Scene s;
    set_stress_view(s, {0, 0, 0}, 3.0);
    const std::uint64_t n = saturating_mul(8, saturating_pow(2, o.size));
    std::vector<SphereSpec> spheres;
    spheres.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        spheres.push_back({{0, 0, 0}, static_cast<double>(i + 1) / static_cast<double>(n)});
    }
    add_spheres(s, spheres, 0, o);
    return s;
}

GenCounts soup_counts(const GenOptions& o) {
    return triangle_counts(soup_count(o.size));
}

}  // namespace

Generator soup_generator() {
    return {"soup",
            "uniform random triangle soup in the unit cube (seeded)",
            "triangles = 1024*2^SF (SF 6: 65536)",
            0,
            6,
            24,
            soup_counts,
            make_soup};
}

Generator soup_clustered_generator() {
    return {"soup_clustered",
            "random triangles in 16 dense Gaussian clusters (seeded)",
            "triangles = 1024*2^SF (SF 6: 65536)",
            0,
            6,
            24,
            soup_counts,
            make_soup_clustered};
}

Generator stadium_generator() {
    return {"stadium",
            "teapot in a stadium: a dense sphere of radius 0.01 inside an empty box of side 2000",
            "triangles = 12*4^SF + 12 (SF 5: 12300)",
            0,
            5,
            12,
            stadium_counts,
            make_stadium};
}

Generator slivers_generator() {
    return {"slivers",
            "needle triangles with aspect ratios up to 1e6 (seeded)",
            "triangles = 1024*2^SF (SF 6: 65536)",
            0,
            6,
            24,
            soup_counts,
            make_slivers};
}

Generator intgrid_generator() {
    return {
        "intgrid",
        "closed cube surface on the integer lattice: axis-aligned rays hit shared edges exactly",
        "triangles = 12*4^SF (SF 4: 3072), vertices 6*4^SF + 2",
        0,
        4,
        13,
        intgrid_counts,
        make_intgrid};
}

Generator scales_generator() {
    return {"scales",
            "spheres of radius 1e-6 ... 1e6, 2^SF per decade",
            "spheres = 13*2^SF (SF 3: 104); mesh: spheres * tess triangles",
            0,
            3,
            20,
            scales_counts,
            make_scales};
}

Generator coplanar_generator() {
    return {"coplanar",
            "overlapping triangles in the plane z = 0, every 8th duplicated (seeded)",
            "triangles = 1024*2^SF (SF 4: 16384)",
            0,
            4,
            24,
            soup_counts,
            make_coplanar};
}

Generator nested_generator() {
    return {"nested",
            "concentric spheres at the origin",
            "spheres = 8*2^SF (SF 3: 64); mesh: spheres * tess triangles",
            0,
            3,
            24,
            nested_counts,
            make_nested};
}

}  // namespace rtlab::gen
