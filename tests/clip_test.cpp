// clip_triangle_bounds (trace/clip.h), the clip of kd-tree perfect splits and SBVH spatial splits:
// its bounds must contain the exact part of the triangle inside the box (Sutherland-Hodgman in
// rationals), on triangles with shared and axis-parallel coordinates and boxes whose planes lie
// on, or a few ulps beside, the triangle's coordinates.
#include "trace/clip.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <gmpxx.h>
#include <random>
#include <vector>

namespace {

using ExactPoint = std::array<mpq_class, 3>;

/// The exact part of triangle (a, b, c) inside box, as a polygon.
std::vector<ExactPoint> exact_clip(const std::array<rtlab::Vec3f, 3>& tri,
                                   const rtlab::Bounds3f& box) {
    std::vector<ExactPoint> poly;
    for (const rtlab::Vec3f& v : tri) {
        poly.push_back({mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)});
    }
    for (std::size_t axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const mpq_class plane(side == 0 ? box.lo[axis] : box.hi[axis]);
            const auto inside = [&](const ExactPoint& p) {
                return side == 0 ? p[axis] >= plane : p[axis] <= plane;
            };
            std::vector<ExactPoint> next;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const ExactPoint& p = poly[i];
                const ExactPoint& q = poly[(i + 1) % poly.size()];
                if (inside(p)) {
                    next.push_back(p);
                }
                if (inside(p) != inside(q)) {
                    const mpq_class s = (plane - p[axis]) / (q[axis] - p[axis]);
                    ExactPoint x;
                    for (std::size_t k = 0; k < 3; ++k) {
                        x[k] = p[k] + (q[k] - p[k]) * s;
                    }
                    next.push_back(x);
                }
            }
            poly = std::move(next);
        }
    }
    return poly;
}

}  // namespace

TEST_CASE("clip_triangle_bounds contains the exact part of the triangle in the box",
          "[accel][clip]") {
    std::mt19937 rng(0xC11Bu);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> pick(0, 7);
    std::size_t parts = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        CAPTURE(trial);
        // Vertices on a coarse lattice half the time, so edges run parallel to box planes.
        std::array<rtlab::Vec3f, 3> tri;
        for (auto& v : tri) {
            for (std::size_t k = 0; k < 3; ++k) {
                v[k] = pick(rng) < 4 ? std::round(unit(rng) * 8.0f) / 8.0f : unit(rng);
            }
        }
        // Planes at a vertex coordinate, a few ulps beside one, or anywhere.
        const auto coordinate = [&](std::size_t k) {
            const float v = tri[static_cast<std::size_t>(pick(rng) % 3)][k];
            switch (pick(rng)) {
            case 0:
            case 1:
                return v;
            case 2:
                return std::nextafter(v, 2.0f);
            case 3:
                return std::nextafter(std::nextafter(v, -2.0f), -2.0f);
            case 4:
                return v + 1e-5f * unit(rng);
            default:
                return unit(rng);
            }
        };
        rtlab::Bounds3f box;
        for (std::size_t k = 0; k < 3; ++k) {
            const float p = coordinate(k), q = coordinate(k);
            box.lo[k] = std::min(p, q);
            box.hi[k] = std::max(p, q);
        }
        const std::vector<ExactPoint> exact = exact_clip(tri, box);
        const rtlab::Bounds3f got = rtlab::clip_triangle_bounds(tri[0], tri[1], tri[2], box);
        if (exact.empty()) {
            continue;
        }
        ++parts;
        REQUIRE(!got.empty());
        for (const ExactPoint& p : exact) {
            for (std::size_t k = 0; k < 3; ++k) {
                CAPTURE(k, p[k].get_d(), got.lo[k], got.hi[k]);
                REQUIRE(mpq_class(got.lo[k]) <= p[k]);
                REQUIRE(p[k] <= mpq_class(got.hi[k]));
            }
        }
        // Inside the box, as the kd-tree and SBVH builders need.
        for (std::size_t k = 0; k < 3; ++k) {
            REQUIRE(got.lo[k] >= box.lo[k]);
            REQUIRE(got.hi[k] <= box.hi[k]);
        }
    }
    CHECK(parts > 5000);
}
