// Sphere flake (Haines, "A Proposal for Standard Graphics Environments", IEEE CG&A 1987, SPD
// "balls"): the child offsets and the parent-to-child rotation follow balls.c's rules.
// Breadth-first generation, O(spheres) time and memory.
#include "datasets_gen/sphere_flake.h"

#include "datasets_gen/spd_lib.h"

#include <array>
#include <cmath>
#include <numbers>

namespace rtlab::gen {

std::uint64_t flake_sphere_count(int sf) {
    std::uint64_t pow9 = 1;
    for (int i = 0; i <= sf; ++i) {
        pow9 *= 9;
    }
    return (pow9 - 1) / 8;
}

namespace {

std::array<Vec3d, 9> make_offsets() {
    const double d = 1.0 / std::sqrt(2.0);
    std::array<Vec3d, 3> trio{Vec3d{d, d, 0}, Vec3d{d, 0, -d}, Vec3d{0, d, -d}};
    const spd::Mat4 tilt =
        spd::rotate_about(normalize(Vec3d{1, -1, 0}), std::asin(2.0 / std::sqrt(6.0)));
    for (Vec3d& t : trio) {
        t = spd::transform_point(t, tilt);
    }
    std::array<Vec3d, 9> out;
    for (std::size_t set = 0; set < 3; ++set) {
        const spd::Mat4 turn =
            spd::rotate(2, static_cast<double>(set) * 2.0 * std::numbers::pi / 3.0);
        for (std::size_t v = 0; v < 3; ++v) {
            out[set * 3 + v] = spd::transform_point(trio[v], turn);
        }
    }
    return out;
}

}  // namespace

Vec3d flake_child_offset(int k) {
    static const std::array<Vec3d, 9> offsets = make_offsets();
    return offsets[static_cast<std::size_t>(k)];
}

Vec3d flake_rotate(const Vec3d& d, const Vec3d& o) {
    if (d.z >= 0.9999) {
        return o;
    }
    if (d.z <= -0.9999) {
        return spd::transform_point(o, spd::rotate(1, std::numbers::pi));
    }
    const Vec3d axis = normalize(cross(Vec3d{0, 0, 1}, d));
    return spd::transform_point(o, spd::rotate_about(axis, std::acos(d.z)));
}

std::vector<FlakeSphere> sphere_flake(int sf) {
    std::vector<FlakeSphere> spheres;
    spheres.reserve(flake_sphere_count(sf));
    spheres.push_back({{0, 0, 0}, 0.5, {0, 0, 1}, 0, 0});
    std::size_t level_begin = 0;
    for (int level = 1; level <= sf; ++level) {
        const std::size_t level_end = spheres.size();
        for (std::size_t p = level_begin; p < level_end; ++p) {
            const FlakeSphere parent = spheres[p];  // copy: push_back may reallocate
            const double scale = parent.radius * (1.0 + 1.0 / 3.0);
            for (int k = 0; k < 9; ++k) {
                // As balls.c: the child's direction is its offset from the parent over `scale`.
                const Vec3d c =
                    flake_rotate(parent.axis, flake_child_offset(k)) * scale + parent.center;
                spheres.push_back({c, parent.radius / 3.0, (c - parent.center) / scale,
                                   static_cast<std::uint32_t>(p),
                                   static_cast<std::uint32_t>(level)});
            }
        }
        level_begin = level_end;
    }
    return spheres;
}

}  // namespace rtlab::gen
