// Adversarial ray sets for certified triangle hits (tests/support/exact_ray_sets.h).
#include "support/exact_ray_sets.h"

#include "intersect/triangle/sphere_mesh.h"

#include <cmath>
#include <limits>
#include <random>

namespace rtlab::test {

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(std::uint64_t seed) : gen(seed) {}
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(gen() >> 11) * 0x1.0p-53;
    }
    int integer(int lo, int hi) { return lo + static_cast<int>(gen() % (hi - lo + 1)); }
    float f(double lo, double hi) { return static_cast<float>(uniform(lo, hi)); }
    Vec3f vec(double lo, double hi) { return {f(lo, hi), f(lo, hi), f(lo, hi)}; }
};

/// Windows cycled over a set's rays: open, [0, 1] (1 is the aimed point's t in the lattice
/// sets), [1, inf), the single point [1, 1], and [0, just below 1].
Rayf with_window(Vec3f org, Vec3f dir, std::size_t k) {
    constexpr float below_one = 0x1.fffffep-1f;
    const float tmins[] = {0.0f, 0.0f, 1.0f, 1.0f, 0.0f};
    const float tmaxs[] = {inf, 1.0f, inf, 1.0f, below_one};
    return {org, dir, tmins[k % 5], tmaxs[k % 5]};
}

/// Integer height of the lattice terrain at (i, j): a few slopes, so edges are not all level.
int height(int i, int j) {
    return (i * j + i) % 3 - 1;
}

/// An n x n lattice terrain scaled by s (a power of two: every vertex and edge midpoint is exact),
/// two triangles per cell split along the (i, j)-(i+1, j+1) diagonal.
std::vector<Trianglef> lattice(int n, float s) {
    std::vector<Trianglef> tris;
    const auto p = [&](int i, int j) {
        return Vec3f{static_cast<float>(i) * s, static_cast<float>(j) * s,
                     static_cast<float>(height(i, j)) * s};
    };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            tris.push_back({p(i, j), p(i + 1, j), p(i + 1, j + 1)});
            tris.push_back({p(i, j), p(i + 1, j + 1), p(i, j + 1)});
        }
    }
    return tris;
}

/// Every vertex and every edge midpoint of the lattice terrain (exact floats).
std::vector<Vec3f> lattice_targets(int n, float s) {
    std::vector<Vec3f> out;
    const auto p = [&](double i, double j, double h) {
        return Vec3f{static_cast<float>(i) * s, static_cast<float>(j) * s,
                     static_cast<float>(h) * s};
    };
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            out.push_back(p(i, j, height(i, j)));
            if (i < n) {
                out.push_back(p(i + 0.5, j, 0.5 * (height(i, j) + height(i + 1, j))));
            }
            if (j < n) {
                out.push_back(p(i, j + 0.5, 0.5 * (height(i, j) + height(i, j + 1))));
            }
            if (i < n && j < n) {
                out.push_back(p(i + 0.5, j + 0.5, 0.5 * (height(i, j) + height(i + 1, j + 1))));
            }
        }
    }
    return out;
}

}  // namespace

/// Random triangles in [-1, 1]^3, a few repeated at the end (exact ties), and random rays with
/// random windows.
RaySet random_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"random", {}, {}};
    for (int i = 0; i < 48; ++i) {
        set.tris.push_back({rng.vec(-1, 1), rng.vec(-1, 1), rng.vec(-1, 1)});
    }
    for (int i = 0; i < 4; ++i) {
        set.tris.push_back(set.tris[static_cast<std::size_t>(i) * 5]);
    }
    for (int i = 0; i < 1000; ++i) {
        const float tmin = i % 3 == 0 ? rng.f(-1, 1) : 0.0f;
        const float tmax = i % 4 == 0 ? rng.f(0, 4) : inf;
        set.rays.push_back({rng.vec(-2, 2), rng.vec(-1, 1), tmin, tmax});
    }
    return set;
}

/// Random triangles in [-1, 1]^3 seen from origins about 2^30 away, aimed exactly through the
/// centre (dir = -org): the vertices' offsets from the origin are not exact in double.
RaySet far_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"far origins", random_set(seed).tris, {}};
    for (int i = 0; i < 300; ++i) {
        Vec3f org = rng.vec(0x1.0p30, 0x1.0p31);
        for (std::size_t k = 0; k < 3; ++k) {
            org[k] = rng.integer(0, 1) == 0 ? -org[k] : org[k];
        }
        set.rays.push_back({org, -org, 0.0f, inf});
    }
    return set;
}

/// Rays aimed exactly at lattice vertices and edge midpoints (origin = target + offset, dir =
/// -offset, both exact, so the target is at t = 1), plus rays from random float origins whose
/// rounded direction passes near the target.
RaySet lattice_set(std::uint64_t seed, float s) {
    Rng rng(seed);
    constexpr int n = 4;
    RaySet set{"lattice s=" + std::to_string(s), lattice(n, s), {}};
    std::size_t k = 0;
    for (const Vec3f& t : lattice_targets(n, s)) {
        for (int rep = 0; rep < 2; ++rep) {
            const Vec3f off{static_cast<float>(rng.integer(-3, 3)) * s,
                            static_cast<float>(rng.integer(-3, 3)) * s,
                            static_cast<float>(rng.integer(1, 5)) * s};
            set.rays.push_back(with_window(t + off, -off, k++));
        }
        const Vec3f org = rng.vec(-1, 5) * s + Vec3f{0, 0, 3 * s};
        set.rays.push_back({org, t - org, 0.0f, inf});
    }
    return set;
}

/// Axis-aligned rays at the lattice targets: straight down and up (two zero components), along
/// x and y at the target's height (grazing the terrain), diagonal in xz and yz (one zero), and
/// down with a denormal x component.
RaySet axis_set(float s) {
    constexpr int n = 4;
    RaySet set{"axis-aligned s=" + std::to_string(s), lattice(n, s), {}};
    const Vec3f dirs[] = {{0, 0, -1}, {0, 0, 1},   {1, 0, 0},           {0, -1, 0},
                          {1, 0, -1}, {0, -1, -1}, {0x1.0p-140f, 0, -1}};  // a denormal component
    std::size_t k = 0;
    for (const Vec3f& t : lattice_targets(n, s)) {
        for (const Vec3f& d : dirs) {
            const Vec3f dir = d * s;
            set.rays.push_back(with_window(t - dir * 2.0f, dir * 2.0f, k++));
        }
    }
    return set;
}

/// The perturbed closed sphere: rays from the centre aimed exactly at every vertex (the origin
/// is 0, so dir = vertex is exact), near edge midpoints, and from random inner points.
RaySet sphere_set(std::uint64_t seed) {
    Rng rng(seed);
    const IndexedMesh mesh = perturbed_sphere_mesh(seed, 8, 12);
    RaySet set{"sphere", {}, {}};
    for (const auto& f : mesh.faces) {
        set.tris.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
    }
    for (const Vec3f& v : mesh.vertices) {
        set.rays.push_back({{0, 0, 0}, v, 0.0f, inf});
        set.rays.push_back({{0, 0, 0}, v, 0.0f, 1.0f});  // the vertex at t = 1 exactly
    }
    for (std::size_t i = 0; i < 120; ++i) {
        const auto& f = mesh.faces[i % mesh.faces.size()];
        const Vec3f mid = (mesh.vertices[f[0]] + mesh.vertices[f[1]]) * 0.5f;
        const Vec3f org = i % 2 == 0 ? Vec3f{0, 0, 0} : rng.vec(-0.3, 0.3);
        set.rays.push_back({org, mid - org, 0.0f, inf});
    }
    return set;
}

/// The perturbed sphere with vertices on the 2^-20 grid, so that sums stay exact floats: rays
/// from grid points inside aimed exactly at every vertex (dir = v - org) and at every edge's
/// midpoint (dir = v_i + v_j - 2 org, the midpoint at t = 1/2). Products of three coordinates
/// need more than 53 bits here, so the double filter rounds.
RaySet quantized_sphere_set(std::uint64_t seed) {
    Rng rng(seed);
    IndexedMesh mesh = perturbed_sphere_mesh(seed, 8, 12);
    const auto grid = [](float x) { return std::round(x * 0x1.0p20f) * 0x1.0p-20f; };
    for (Vec3f& v : mesh.vertices) {
        v = {grid(v.x), grid(v.y), grid(v.z)};
    }
    RaySet set{"quantized sphere", {}, {}};
    for (const auto& f : mesh.faces) {
        set.tris.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
    }
    const auto org = [&] {
        const Vec3f o = rng.vec(-0.25, 0.25);
        return Vec3f{grid(o.x), grid(o.y), grid(o.z)};
    };
    for (const Vec3f& v : mesh.vertices) {
        const Vec3f o = org();
        set.rays.push_back({o, v - o, 0.0f, inf});
    }
    for (const auto& f : mesh.faces) {
        const Vec3f o = org();
        const Vec3f vi = mesh.vertices[f[0]], vj = mesh.vertices[f[1]];
        set.rays.push_back({o, vi + vj - o * 2.0f, 0.0f, inf});
    }
    return set;
}

/// Integer triangles in tilted planes with rays lying exactly in a triangle's plane (origin and
/// direction integer combinations of its edges: coplanar, a miss by rule), and the same rays with
/// the direction or the origin moved by one ulp in one component (grazing).
RaySet grazing_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"grazing", {}, {}};
    const auto ivec = [&] {
        return Vec3f{static_cast<float>(rng.integer(-8, 8)), static_cast<float>(rng.integer(-8, 8)),
                     static_cast<float>(rng.integer(-8, 8))};
    };
    while (set.tris.size() < 16) {
        const Trianglef t{ivec(), ivec(), ivec()};
        if (!is_degenerate(t.p0, t.p1, t.p2)) {
            set.tris.push_back(t);
        }
    }
    for (const Trianglef& t : set.tris) {
        const Vec3f e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
        for (int r = 0; r < 6; ++r) {
            const auto a = static_cast<float>(rng.integer(-2, 2));
            const auto b = static_cast<float>(rng.integer(-2, 2));
            const Vec3f org = t.p0 + e1 * a + e2 * b;
            Vec3f dir = e1 * static_cast<float>(rng.integer(-2, 2)) +
                        e2 * static_cast<float>(rng.integer(-2, 2));
            if (dir == Vec3f{0, 0, 0}) {
                dir = t.p2 - t.p1;
            }
            const auto axis = static_cast<std::size_t>(r % 3);
            Vec3f dir_ulp = dir, org_ulp = org;
            dir_ulp[axis] = std::nextafter(dir[axis], r < 3 ? inf : -inf);
            org_ulp[axis] = std::nextafter(org[axis], r < 3 ? -inf : inf);
            set.rays.push_back({org, dir, -inf, inf});
            set.rays.push_back({org, dir_ulp, -inf, inf});
            set.rays.push_back({org_ulp, dir, -inf, inf});
        }
    }
    return set;
}

/// Origins on the lattice surface (vertices, edge midpoints, and points inside triangles with
/// dyadic barycentrics), random directions, windows starting at 0 (so t = 0 is a hit).
RaySet surface_set(std::uint64_t seed, float s) {
    Rng rng(seed);
    constexpr int n = 4;
    RaySet set{"surface origins s=" + std::to_string(s), lattice(n, s), {}};
    std::vector<Vec3f> origins = lattice_targets(n, s);
    for (const Trianglef& t : set.tris) {
        origins.push_back(t.p0 + (t.p1 - t.p0) * 0.25f + (t.p2 - t.p0) * 0.5f);
    }
    for (const Vec3f& o : origins) {
        set.rays.push_back({o, rng.vec(-1, 1) * s, 0.0f, inf});
    }
    return set;
}

std::vector<RaySet> exact_ray_sets() {
    std::vector<RaySet> out{random_set(11), far_set(13), sphere_set(31), quantized_sphere_set(37),
                            grazing_set(41)};
    for (const float s : {1.0f, 0x1.0p-20f, 0x1.0p20f}) {
        out.push_back(lattice_set(21, s));
        out.push_back(axis_set(s));
        out.push_back(surface_set(51, s));
    }
    return out;
}

}  // namespace rtlab::test
