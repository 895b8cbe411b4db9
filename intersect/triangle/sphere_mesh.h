#pragma once
// A closed, vertex-perturbed UV sphere with shared vertices, in float: the fixture for
// watertightness tests and the triangle cross-check (pbrt's "Triangle, Watertight" idea).

#include "intersect/triangle/triangle.h"
#include "intersect/vec.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace rtlab {

/// An indexed triangle mesh; every edge of a closed mesh is shared by exactly two triangles.
struct IndexedMesh {
    std::vector<Vec3f> vertices;                      ///< shared vertex positions
    std::vector<std::array<std::uint32_t, 3>> faces;  ///< vertex indices, consistently wound

    /// Triangle i in scalar T (float -> double is exact).
    template <class T>
    Triangle<T> triangle(std::size_t i) const {
        const auto& f = faces[i];
        return {Vec3<T>(vertices[f[0]]), Vec3<T>(vertices[f[1]]), Vec3<T>(vertices[f[2]])};
    }
};

/// A closed UV sphere around the origin with `rings` latitude bands and `segments` longitude
/// steps (2 * segments * (rings - 1) triangles); each vertex radius is 1 + jitter * r with r
/// uniform in [-1, 1], seeded. jitter must be < 1 so the origin stays inside.
inline IndexedMesh perturbed_sphere_mesh(std::uint64_t seed,
                                         std::uint32_t rings = 12,
                                         std::uint32_t segments = 16,
                                         double jitter = 0.1) {
    std::mt19937_64 rng(seed);
    const auto uniform_pm1 = [&rng] {
        return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0;  // [-1, 1)
    };
    IndexedMesh m;
    const auto add = [&](double x, double y, double z) {
        const double r = 1.0 + jitter * uniform_pm1();
        m.vertices.push_back(
            Vec3f{static_cast<float>(x * r), static_cast<float>(y * r), static_cast<float>(z * r)});
    };
    add(0, 0, 1);  // north pole, index 0
    for (std::uint32_t i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * i / rings;
        for (std::uint32_t j = 0; j < segments; ++j) {
            const double phi = 2 * std::numbers::pi * j / segments;
            add(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        }
    }
    add(0, 0, -1);  // south pole
    const auto ring = [segments](std::uint32_t i, std::uint32_t j) {
        return 1 + (i - 1) * segments + j % segments;
    };
    const std::uint32_t south = static_cast<std::uint32_t>(m.vertices.size() - 1);
    for (std::uint32_t j = 0; j < segments; ++j) {
        m.faces.push_back({0, ring(1, j), ring(1, j + 1)});
        for (std::uint32_t i = 1; i + 1 < rings; ++i) {
            m.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        m.faces.push_back({ring(rings - 1, j), south, ring(rings - 1, j + 1)});
    }
    return m;
}

}  // namespace rtlab
