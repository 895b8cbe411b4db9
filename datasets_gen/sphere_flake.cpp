// Sphere flake (Haines, "A Proposal for Standard Graphics Environments", IEEE CG&A 1987, SPD
// "balls"). Breadth-first generation, O(spheres) time and memory.
#include "datasets_gen/sphere_flake.h"

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

Vec3d flake_child_offset(int k) {
    const double deg = std::numbers::pi / 180.0;
    double azimuth = 0;
    double elevation = 0;
    if (k < 6) {
        azimuth = (15.0 + 60.0 * k) * deg;
    } else {
        azimuth = (45.0 + 120.0 * (k - 6)) * deg;
        elevation = std::asin(std::sqrt(2.0 / 3.0));
    }
    const double c = std::cos(elevation);
    return {c * std::cos(azimuth), c * std::sin(azimuth), std::sin(elevation)};
}

void flake_frame(const Vec3d& axis, Vec3d& u, Vec3d& v) {
    const Vec3d helper = std::abs(axis.y) > 0.9 ? Vec3d{0, 0, 1} : Vec3d{0, 1, 0};
    u = normalize(cross(helper, axis));
    v = cross(axis, u);
}

std::vector<FlakeSphere> sphere_flake(int sf) {
    std::vector<FlakeSphere> spheres;
    spheres.reserve(flake_sphere_count(sf));
    spheres.push_back({{0, 0, 0}, 0.5, {0, 0, 1}, 0, 0});
    Vec3d offsets[9];
    for (int k = 0; k < 9; ++k) {
        offsets[k] = flake_child_offset(k);
    }
    std::size_t level_begin = 0;
    for (int level = 1; level <= sf; ++level) {
        const std::size_t level_end = spheres.size();
        for (std::size_t p = level_begin; p < level_end; ++p) {
            const FlakeSphere parent = spheres[p];  // copy: push_back may reallocate
            const double r = parent.radius / 3.0;
            Vec3d u;
            Vec3d v;
            flake_frame(parent.axis, u, v);
            for (const Vec3d& o : offsets) {
                // Rotate the offset into the parent's frame; renormalise against rounding drift.
                const Vec3d dir = normalize(u * o.x + v * o.y + parent.axis * o.z);
                spheres.push_back({parent.center + dir * (parent.radius + r), r, dir,
                                   static_cast<std::uint32_t>(p),
                                   static_cast<std::uint32_t>(level)});
            }
        }
        level_begin = level_end;
    }
    return spheres;
}

}  // namespace rtlab::gen
