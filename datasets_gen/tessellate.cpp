// Sphere tessellation. UV spheres: latitude-longitude grid with triangle fans at the poles. Cube
// spheres: the N x N grid on each cube face mapped equi-angularly (x -> tan(x * pi/4)) and
// projected onto the sphere, so cells are near-uniform and there are no poles. O(triangles) time.
#include "datasets_gen/tessellate.h"

#include "base/error.h"
#include "intersect/cone/cone.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <span>
#include <unordered_map>

namespace rtlab::gen {

namespace {

using Tri = std::array<std::uint32_t, 3>;

/// A unit-sphere (or lattice) template in double precision, scaled and moved per instance.
struct Template {
    std::vector<Vec3d> positions;
    std::vector<Tri> triangles;
};

int parse_int(std::string_view s, std::string_view whole) {
    int value = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) {
        throw Error("bad tessellation '" + std::string(whole) +
                    "': expected uv:UxV (e.g. uv:16x8) or cube:N (e.g. cube:8)");
    }
    return value;
}

/// Unit sphere as a UV grid: vertex 0 is the +Z pole, then rings from north to south, then -Z.
Template uv_unit_sphere(int nu, int nv) {
    Template m;
    const double pi = std::numbers::pi;
    m.positions.push_back({0, 0, 1});
    for (int j = 1; j < nv; ++j) {
        const double theta = pi * j / nv;
        for (int i = 0; i < nu; ++i) {
            const double phi = 2 * pi * i / nu;
            m.positions.push_back({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                   std::cos(theta)});
        }
    }
    m.positions.push_back({0, 0, -1});
    const auto ring = [nu](int j, int i) {
        return static_cast<std::uint32_t>(1 + (j - 1) * nu + (i % nu));
    };
    const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
    for (int i = 0; i < nu; ++i) {
        m.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
    }
    for (int j = 1; j + 1 < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            // Down (south) then east is outward-facing counter-clockwise.
            m.triangles.push_back({ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)});
            m.triangles.push_back({ring(j, i), ring(j + 1, i + 1), ring(j, i + 1)});
        }
    }
    for (int i = 0; i < nu; ++i) {
        m.triangles.push_back({south, ring(nv - 1, i + 1), ring(nv - 1, i)});
    }
    return m;
}

/// Surface of the lattice cube [0,n]^3 with unit squares split in two, vertices shared across
/// faces (keyed by their lattice point), winding outward. Positions are lattice coordinates.
Template lattice_cube(int n) {
    Template m;
    const auto side = static_cast<std::uint64_t>(n) + 1;
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(static_cast<std::size_t>(6 * side * side));
    const auto vertex = [&](const std::array<int, 3>& p) {
        const std::uint64_t key =
            (static_cast<std::uint64_t>(p[0]) * side + static_cast<std::uint64_t>(p[1])) * side +
            static_cast<std::uint64_t>(p[2]);
        const auto [it, inserted] =
            index.try_emplace(key, static_cast<std::uint32_t>(m.positions.size()));
        if (inserted) {
            m.positions.push_back(
                {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])});
        }
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int b = (axis + 1) % 3;
        const int c = (axis + 2) % 3;
        for (int side_sign = 0; side_sign < 2; ++side_sign) {
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    std::array<std::array<int, 3>, 4> q{};
                    const int di[4] = {0, 1, 1, 0};
                    const int dj[4] = {0, 0, 1, 1};
                    for (int k = 0; k < 4; ++k) {
                        q[k][axis] = side_sign * n;
                        q[k][b] = i + di[k];
                        q[k][c] = j + dj[k];
                    }
                    // (b, c, axis) is a right-handed cyclic order, so q winds counter-clockwise
                    // seen from +axis: outward on the far face, reversed on the near one.
                    std::array<std::uint32_t, 4> v{vertex(q[0]), vertex(q[1]), vertex(q[2]),
                                                   vertex(q[3])};
                    if (side_sign == 0) {
                        std::swap(v[1], v[3]);
                    }
                    m.triangles.push_back({v[0], v[1], v[2]});
                    m.triangles.push_back({v[0], v[2], v[3]});
                }
            }
        }
    }
    return m;
}

Template cube_unit_sphere(int n) {
    Template m = lattice_cube(n);
    const double quarter_pi = std::numbers::pi / 4;
    for (Vec3d& p : m.positions) {
        const auto warp = [&](double t) { return std::tan((2 * t / n - 1) * quarter_pi); };
        p = normalize(Vec3d{warp(p.x), warp(p.y), warp(p.z)});
    }
    return m;
}

/// Appends t scaled by `scale` and moved by `offset`, rounding each position to float once.
void append_template(TriangleMesh& out, const Template& t, double scale, const Vec3d& offset) {
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    out.positions.reserve(out.positions.size() + t.positions.size());
    for (const Vec3d& p : t.positions) {
        out.positions.push_back(Vec3f(offset + p * scale));
    }
    out.triangles.reserve(out.triangles.size() + t.triangles.size());
    for (const Tri& tri : t.triangles) {
        out.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
    }
}

Template unit_sphere(const SphereTess& tess) {
    return tess.kind == SphereTess::Kind::uv ? uv_unit_sphere(tess.u, tess.v)
                                             : cube_unit_sphere(tess.n);
}

}  // namespace

void append_mesh(TriangleMesh& out, const TriangleMesh& other) {
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    out.positions.insert(out.positions.end(), other.positions.begin(), other.positions.end());
    out.triangles.reserve(out.triangles.size() + other.triangles.size());
    for (const Tri& t : other.triangles) {
        out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
}

std::uint64_t SphereTess::triangles() const {
    if (kind == Kind::uv) {
        return 2ull * static_cast<std::uint64_t>(u) * static_cast<std::uint64_t>(v - 2) +
               2ull * static_cast<std::uint64_t>(u);
    }
    return 12ull * static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n);
}

std::uint64_t SphereTess::vertices() const {
    if (kind == Kind::uv) {
        return static_cast<std::uint64_t>(u) * static_cast<std::uint64_t>(v - 1) + 2;
    }
    return 6ull * static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n) + 2;
}

std::string SphereTess::to_string() const {
    if (kind == Kind::uv) {
        return "uv:" + std::to_string(u) + "x" + std::to_string(v);
    }
    return "cube:" + std::to_string(n);
}

SphereTess parse_sphere_tess(std::string_view text) {
    SphereTess t;
    if (text.starts_with("uv:")) {
        const std::string_view rest = text.substr(3);
        const std::size_t x = rest.find('x');
        if (x == std::string_view::npos) {
            parse_int("", text);  // throws the format message
        }
        t.kind = SphereTess::Kind::uv;
        t.u = parse_int(rest.substr(0, x), text);
        t.v = parse_int(rest.substr(x + 1), text);
        if (t.u < 3 || t.u > 4096 || t.v < 2 || t.v > 4096) {
            throw Error("bad tessellation '" + std::string(text) +
                        "': uv:UxV needs 3 <= U <= 4096 and 2 <= V <= 4096");
        }
        return t;
    }
    if (text.starts_with("cube:")) {
        t.kind = SphereTess::Kind::cube;
        t.n = parse_int(text.substr(5), text);
        if (t.n < 1 || t.n > 2048) {
            throw Error("bad tessellation '" + std::string(text) +
                        "': cube:N needs 1 <= N <= 2048");
        }
        return t;
    }
    parse_int("", text);
    return t;
}

void append_sphere(TriangleMesh& out, const Vec3d& center, double radius, const SphereTess& tess) {
    append_template(out, unit_sphere(tess), radius, center);
}

void append_spheres(TriangleMesh& out,
                    std::span<const SphereSpec> spheres,
                    const SphereTess& tess) {
    const Template unit = unit_sphere(tess);
    for (const SphereSpec& s : spheres) {
        append_template(out, unit, s.radius, s.center);
    }
}

void append_cone(TriangleMesh& out,
                 const Vec3d& base,
                 double base_radius,
                 const Vec3d& apex,
                 double apex_radius,
                 bool cap_base,
                 bool cap_apex,
                 int segments) {
    const Vec3d axis = normalize(apex - base);
    Vec3d e1, e2;
    detail::orthonormal_frame(axis, e1, e2);
    const auto n = static_cast<std::uint32_t>(segments);
    // One ring per end (a single point when its radius is 0), counter-clockwise about the axis.
    const auto ring = [&](const Vec3d& c, double r) {
        const auto start = static_cast<std::uint32_t>(out.positions.size());
        if (r == 0) {
            out.positions.push_back(Vec3f(c));
            return start;
        }
        for (std::uint32_t i = 0; i < n; ++i) {
            const double phi = 2 * std::numbers::pi * i / n;
            out.positions.push_back(Vec3f(c + (e1 * std::cos(phi) + e2 * std::sin(phi)) * r));
        }
        return start;
    };
    const std::uint32_t b = ring(base, base_radius);
    const std::uint32_t a = ring(apex, apex_radius);
    const auto bi = [&](std::uint32_t i) { return base_radius == 0 ? b : b + i % n; };
    const auto ai = [&](std::uint32_t i) { return apex_radius == 0 ? a : a + i % n; };
    for (std::uint32_t i = 0; i < n; ++i) {
        // (b_i, b_i+1, a_i+1) winds outward: tangent x axis = radial.
        if (base_radius != 0) {
            out.triangles.push_back({bi(i), bi(i + 1), ai(i + 1)});
        }
        if (apex_radius != 0) {
            out.triangles.push_back({bi(i), ai(i + 1), ai(i)});
        }
    }
    const auto fan = [&](const Vec3d& c, std::uint32_t start, bool outward_is_axis) {
        const auto centre = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(Vec3f(c));
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t p = start + i, q = start + (i + 1) % n;
            out.triangles.push_back(outward_is_axis ? std::array<std::uint32_t, 3>{centre, p, q}
                                                    : std::array<std::uint32_t, 3>{centre, q, p});
        }
    };
    if (cap_base && base_radius != 0) {
        fan(base, b, false);
    }
    if (cap_apex && apex_radius != 0) {
        fan(apex, a, true);
    }
}

void append_integer_cube(TriangleMesh& out, int n, const Vec3d& origin) {
    append_template(out, lattice_cube(n), 1.0, origin);
}

bool is_closed_manifold(const TriangleMesh& mesh) {
    std::vector<std::uint64_t> directed;
    directed.reserve(mesh.triangles.size() * 3);
    for (const Tri& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[static_cast<std::size_t>(k)];
            const std::uint32_t b = t[static_cast<std::size_t>((k + 1) % 3)];
            if (a == b || a >= mesh.positions.size() || b >= mesh.positions.size()) {
                return false;
            }
            directed.push_back(static_cast<std::uint64_t>(a) << 32 | b);
        }
    }
    std::sort(directed.begin(), directed.end());
    // Each directed edge once (consistent orientation), and its reverse present (closed).
    if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) {
        return false;
    }
    return std::all_of(directed.begin(), directed.end(), [&](std::uint64_t e) {
        const std::uint64_t rev = (e & 0xffffffffull) << 32 | (e >> 32);
        return std::binary_search(directed.begin(), directed.end(), rev);
    });
}

}  // namespace rtlab::gen
