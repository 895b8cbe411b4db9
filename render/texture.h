#pragma once
// Solid 3-D checkerboard (seed 001): the colour alternates between the material's two colours in
// a lattice of cubes of edge `scale`. Cost: three floors and a parity test.

#include "intersect/vec.h"
#include "scene/scene.h"

#include <cmath>

namespace rtlab {

/// The material's colour at world point p: `color` for plain materials; for a checker, `color`
/// when floor(x/s) + floor(y/s) + floor(z/s) is even, else `texture.color2`, where the lattice is
/// shifted by s/1000 on every axis so a surface lying exactly on a cell face (a floor at y = 0)
/// does not flicker between cells with the rounding noise of its hit points.
inline Vec3f surface_color(const Material& m, const Vec3f& p) {
    if (m.texture.kind != TextureKind::checker) {
        return m.color;
    }
    const float s = m.texture.scale;
    const float shift = 1e-3f;
    const auto cell = [&](float v) { return static_cast<long long>(std::floor(v / s + shift)); };
    const long long sum = cell(p.x) + cell(p.y) + cell(p.z);
    return (sum & 1) == 0 ? m.color : m.texture.color2;
}

}  // namespace rtlab
