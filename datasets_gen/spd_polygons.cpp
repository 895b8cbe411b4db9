// SPD databases (Haines et al., SPD 3.14, public domain) of polygons: gears.c, mount.c,
// sombrero.c, tetra.c, rebuilt from their rules through the SPD library rules of spd_lib.h.
#include "datasets_gen/spd_databases.h"
#include "datasets_gen/spd_lib.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rtlab::gen::spd {

using detail::ipow;
using detail::pi;
using detail::sky_blue;

// ---- gears: an SF x SF x SF stack of 36-tooth gears; each gear is a concave 144-gon top, 144
// side quads and a 144-gon bottom, on a reflective ground square.

namespace {

constexpr int gear_teeth = 36;

// The 4 outline points of one tooth (create_tooth): outer corners at +-0.19 of the tooth angle,
// inner ones at 0.3 and 0.7.
void gear_tooth(double gear_angle,
                double tooth_angle,
                const Vec3d& center,
                const Vec3d& outer,
                const Vec3d& inner,
                std::vector<Vec3d>& out) {
    const double at[4] = {-0.19, 0.19, 0.3, 0.7};
    for (std::size_t k = 0; k < 4; ++k) {
        const Vec3d& p = k < 2 ? outer : inner;
        const Mat4 m = rotate(2, gear_angle + at[k] * tooth_angle);
        out.push_back(transform_point(p, m) + center);
    }
}

void gear(Writer& w,
          const Vec3d& center,
          double offset_angle,
          double outer_r,
          double inner_r,
          double thickness) {
    Vec3d outer{outer_r, 0, 0};
    Vec3d inner{inner_r, 0, 0};
    const double tooth = 2.0 * pi / gear_teeth;
    std::vector<Vec3d> pts;
    for (int t = 0; t < gear_teeth; ++t) {
        gear_tooth(offset_angle + 2.0 * pi * t / gear_teeth, tooth, center, outer, inner, pts);
    }
    w.polygon(pts);
    const std::size_t n = pts.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d& a = pts[i];
        const Vec3d& b = pts[(i + 1) % n];
        w.polygon({a, a - Vec3d{0, 0, thickness}, b - Vec3d{0, 0, thickness}, b});
    }
    outer.z = -thickness;
    inner.z = -thickness;
    pts.clear();
    for (int t = 0; t < gear_teeth; ++t) {
        gear_tooth(offset_angle - 2.0 * pi * t / gear_teeth, -tooth, center, outer, inner, pts);
    }
    w.polygon(pts);
}

double fraction(double a) {
    return a - static_cast<double>(static_cast<long>(a));
}

}  // namespace

nff::Document gears(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({-1.1, -2.1, 2.6}, {0, 0, 0}, {0, 0, 1}, 45, 1, 512, 512);
    for (const Vec3d& l : {Vec3d{2, 4, 4}, Vec3d{-2, 4, 3}, Vec3d{2, -2.5, 2.5}, Vec3d{-1, -4, 2},
                           Vec3d{-1.111, -2.121, 2.626}}) {
        w.light(l);
    }
    w.color({1, 0.85, 0.7}, 0.3, 0.6, 37, 0, 0);
    w.polygon({{2, 2, 0}, {-2, 2, 0}, {-2, -2, 0}, {2, -2, 0}});
    const double edge_diff = 1.0 - 0.9;
    const double n = sf;
    const double outer_r = 1.0 / (n - (n - 1.0) * edge_diff / 2.0);
    const Vec3d zero{-1.0 + outer_r, -1.0 + outer_r, 1.0};
    const Vec3d offset{outer_r * (2.0 - edge_diff), outer_r * (2.0 - edge_diff), -1.0 / n};
    for (int iz = 0; iz < sf; ++iz) {
        for (int iy = 0; iy < sf; ++iy) {
            for (int ix = 0; ix < sf; ++ix) {
                const Vec3d center{zero.x + ix * offset.x, zero.y + iy * offset.y,
                                   zero.z + iz * offset.z};
                Vec3d c{0.01 + fraction((ix * 3 + iy * 2 + iz + 1) * 5.0 / 7.0),
                        0.01 + fraction((iy * 3 + iz * 2 + ix + 1) * 3.0 / 7.0),
                        0.01 + fraction((iz * 3 + ix * 2 + iy + 1) * 2.0 / 7.0)};
                c = c / std::max(std::max(c.x, c.y), c.z);
                if ((ix * 4 + iy * 2 + iz) % 5 == 0) {
                    w.color(c, 0.2, 0, 0, 0.8, 1.1);
                } else {
                    w.color(c, 1, 0, 0, 0, 0);
                }
                const double angle = pi * static_cast<double>((ix + iy + iz) % 2) / gear_teeth;
                const double thickness = std::min(0.1, 1.0 / (2.0 * n));
                gear(w, center, angle, 0.995 * outer_r, (1.0 - edge_diff) * outer_r, thickness);
            }
        }
    }
    return w.take();
}

nff::Counts gears_counts(int sf) {
    const std::uint64_t g = ipow(static_cast<std::uint64_t>(sf), 3);
    return {0, 0, 1 + g * (2 + 4 * gear_teeth),
            0, 5, 4 + g * (2 * 4 * gear_teeth + 4 * 4 * gear_teeth)};
}

// ---- mount: Carpenter's fractal mountain (Fournier, Fussell & Carpenter 1982) over [-1,1]^2 with
// the SPD's midpoint displacement: each edge midpoint and the centre move by a Gaussian deviate
// seeded from a hash of the grid position (the SPD's original, "faulty" hash, kept for
// comparisons), scaled by the half side times the roughness of fractal dimension 2.2; a pyramid
// of 4 glass spheres in front.

namespace {

// The SPD's hash_rand for 64-bit unsigned long; a negative shift count (SF > 7) is taken modulo
// 64, as x86 does (the C code's behaviour there is undefined).
std::uint64_t mount_hash(std::uint64_t a, std::uint64_t b, int c) {
    const auto shl = [](std::uint64_t v, int k) { return v << (static_cast<unsigned>(k) & 63u); };
    return (shl(a, 23 - c) + shl(b, 15 - c) + shl(a, 7 - c)) & 0xffffu;
}

// Numerical Recipes' GASDEV with the SPD's portable congruential generator, seeded by iseed.
double gauss_rand(long iseed) {
    constexpr long m1 = 134456;
    constexpr long ia1 = 8121;
    constexpr long ic1 = 28411;
    long ix2 = iseed;
    double v1 = 0;
    double r = 0;
    do {
        const long ix1 = (ic1 + ix2 * ia1) % m1;
        ix2 = (ic1 + ix1 * ia1) % m1;
        v1 = static_cast<double>(ix1) * 2.0 / m1 - 1.0;
        const double v2 = static_cast<double>(ix2) * 2.0 / m1 - 1.0;
        r = v1 * v1 + v2 * v2;
    } while (r >= 1.0);
    return v1 * std::sqrt(-2.0 * std::log(r) / r);
}

struct Mountain {
    Writer& w;
    int sf;
    double fnum;
    double roughness;

    double deviate(int x, int y) const {
        return gauss_rand(21 + static_cast<long>(mount_hash(static_cast<std::uint64_t>(x),
                                                            static_cast<std::uint64_t>(y), sf)));
    }

    void grow(int width, int llx, int lly, double ll, double lr, double ur, double ul) {
        if (width == 1) {
            const double lx = -1.0 + llx * 2.0 / fnum;
            const double rx = -1.0 + (llx + 1) * 2.0 / fnum;
            const double ly = -1.0 + lly * 2.0 / fnum;
            const double uy = -1.0 + (lly + 1) * 2.0 / fnum;
            const Vec3d c[4] = {{lx, ly, ll}, {rx, ly, lr}, {rx, uy, ur}, {lx, uy, ul}};
            w.polygon({c[0], c[1], c[2]});
            w.polygon({c[2], c[3], c[0]});
            return;
        }
        const int half = width >> 1;
        const double rise = half * 2.0 / fnum * roughness;
        const double lower = (ll + lr) / 2.0 + rise * deviate(llx + half, lly);
        const double right = (lr + ur) / 2.0 + rise * deviate(llx + width, lly + half);
        const double upper = (ur + ul) / 2.0 + rise * deviate(llx + half, lly + width);
        const double left = (ul + ll) / 2.0 + rise * deviate(llx, lly + half);
        const double middle =
            (ll + lr + ur + ul) / 4.0 + 1.4142136 * rise * deviate(llx + half, lly + half);
        grow(half, llx, lly, ll, lower, middle, left);
        grow(half, llx + half, lly, lower, lr, right, middle);
        grow(half, llx + half, lly + half, middle, right, ur, upper);
        grow(half, llx, lly + half, left, middle, upper, ul);
    }
};

}  // namespace

nff::Document mount(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({-1.6, 1.6, 1.7}, {0, 0, 0}, {0, 0, 1}, 45, 0.01, 512, 512);
    w.light({-100, -100, 100});
    w.color({1, 1, 1}, 0.1, 0.1, 6.7, 0.9, 1.5);
    // A pyramid of 4 spheres: one above the centre, three turned down by acos(-1/3) about
    // (1,1,0)/sqrt2, then about Z by thirds of a turn.
    const Vec3d center{-0.8, 0.8, 1.0};
    const double r = 0.17;
    const Vec3d top{0, 0, r * std::sqrt(3.0 / 2.0)};
    w.sphere(center + top, r);
    const Vec3d down =
        transform_point(top, rotate_about(normalize(Vec3d{1, 1, 0}), std::acos(-1.0 / 3.0)));
    for (int i = 0; i < 3; ++i) {
        w.sphere(transform_point(down, rotate(2, i * 2.0 * pi / 3.0)) + center, r);
    }
    w.color({0.5, 0.45, 0.35}, 1, 0, 0, 0, 0);
    const int n = 1 << sf;
    const double ratio = 2.0 / std::exp(std::log(2.0) / (2.2 - 1.0));
    Mountain m{w, sf, static_cast<double>(n), std::sqrt(ratio * ratio - 1.0)};
    m.grow(n, 0, 0, 0, 0, 0, 0);
    return w.take();
}

nff::Counts mount_counts(int sf) {
    const std::uint64_t t = 2 * ipow(4, sf);
    return {4, 0, t, 0, 1, 3 * t};
}

// ---- sombrero: a height field y = 3 cos(2 pi a r) e^(-b r) / 3 over [-4,4]^2 in float, sampled
// with running sums x += dx, written as two triangles per cell (lib_output_polygon_height); the
// output grid spacing is 8/(w-1) while the samples are 8/w apart, as the SPD does.

nff::Document sombrero(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({0, 5, -8}, {0, 0, 0}, {0, 0, 1}, 40, 0.01, 512, 512);
    w.light({10, 10, -10});
    w.color({1, 0.1, 0.1}, 0.8, 0, 40, 0, 1);
    const int n = 32 * (1 << (sf - 1));
    const double two_pi_a = 2.0 * 3.14159265358;  // the SPD's own value of pi
    std::vector<std::vector<float>> data(static_cast<std::size_t>(n),
                                         std::vector<float>(static_cast<std::size_t>(n)));
    const double delta = 8.0 / n;
    double y = -4.0;
    for (std::size_t i = 0; i < data.size(); ++i, y += delta) {
        double x = -4.0;
        for (std::size_t j = 0; j < data.size(); ++j, x += delta) {
            const double r = std::sqrt(x * x + y * y);
            data[i][j] = static_cast<float>(3.0 * std::cos(two_pi_a * r) * std::exp(-r) / 3.0);
        }
    }
    const double step = 8.0 / (n - 1);
    const auto vert = [&](std::size_t i, std::size_t j) {
        return Vec3d{-4.0 + static_cast<double>(j) * step, -3.0 + double(data[i][j]),
                     -4.0 + static_cast<double>(i) * step};
    };
    for (std::size_t i = 0; i + 1 < data.size(); ++i) {
        for (std::size_t j = 0; j + 1 < data.size(); ++j) {
            w.polygon({vert(i, j), vert(i + 1, j + 1), vert(i, j + 1)});
            w.polygon({vert(i, j), vert(i + 1, j), vert(i + 1, j + 1)});
        }
    }
    return w.take();
}

nff::Counts sombrero_counts(int sf) {
    const std::uint64_t n = 32 * ipow(2, sf - 1);
    return {0, 0, 2 * (n - 1) * (n - 1), 0, 1, 6 * (n - 1) * (n - 1)};
}

// ---- tetra: Sierpinski tetrahedron (Glassner 1984; Kay & Kajiya 1986): SF-1 levels of four
// half-size tetrahedra at alternate cube corners; leaves give 4 triangles each.

namespace {

void tetra_recurse(Writer& w, int depth, const Vec3d& c, double half) {
    std::vector<Vec3d> corners;
    for (int x = -1; x <= 1; x += 2) {
        for (int y = -1; y <= 1; y += 2) {
            for (int z = -1; z <= 1; z += 2) {
                if (x * y * z == 1) {
                    corners.push_back(c + Vec3d{double(x), double(y), double(z)} *
                                              (depth <= 1 ? half : half / 2.0));
                }
            }
        }
    }
    if (depth > 1) {
        for (const Vec3d& sub : corners) {
            tetra_recurse(w, depth - 1, sub, half / 2.0);
        }
        return;
    }
    // Face f uses corners f, f+1, f+2 (mod 4), reversed for odd f: outward winding.
    for (int f = 0; f < 4; ++f) {
        std::array<int, 3> o{f % 4, (f + 1) % 4, (f + 2) % 4};
        if (f % 2 == 1) {
            std::swap(o[0], o[2]);
        }
        w.polygon({corners[static_cast<std::size_t>(o[0])], corners[static_cast<std::size_t>(o[1])],
                   corners[static_cast<std::size_t>(o[2])]});
    }
}

}  // namespace

nff::Document tetra(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({1.022846, -3.177154, -2.174512}, {-0.004103, -0.004103, 0.216539},
           {-0.816497, -0.816497, 0.816497}, 45, 1, 512, 512);
    w.light({2, -18, -5});
    w.color({1, 0.2, 0.2}, 1, 0, 0, 0, 0);
    tetra_recurse(w, sf, {0, 0, 0}, 1.0);
    return w.take();
}

nff::Counts tetra_counts(int sf) {
    return {0, 0, ipow(4, sf), 0, 1, 3 * ipow(4, sf)};
}

}  // namespace rtlab::gen::spd
