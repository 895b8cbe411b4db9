#pragma once
// Pinhole camera rays: the image plane spans the vertical field of view; pixel (0, 0) is the top
// left corner, x to the right, y down, continuous coordinates in [0, width] x [0, height].

#include "intersect/ray.h"
#include "scene/scene.h"

#include <cmath>
#include <numbers>

namespace rtlab {

/// The camera's orthonormal frame and image-plane scale, computed once per image.
struct CameraFrame {
    Vec3f origin, forward, right, up;
    float tan_half_fov = 1;
    float aspect = 1;

    /// Frame of a camera (from, at, up must not be degenerate; the scene loader checks that).
    explicit CameraFrame(const Camera& c)
        : origin(c.from)
        , forward(normalize(c.at - c.from))
        , right(normalize(cross(forward, c.up)))
        , up(cross(right, forward))
        , tan_half_fov(std::tan(c.fov_deg * std::numbers::pi_v<float> / 360.0f))
        , aspect(static_cast<float>(c.width) / static_cast<float>(c.height)) {}

    /// The ray through image point (px, py) of a width x height image; unit direction.
    Rayf ray(float px, float py, int width, int height) const {
        const float sx = (2.0f * px / static_cast<float>(width) - 1.0f) * tan_half_fov * aspect;
        const float sy = (1.0f - 2.0f * py / static_cast<float>(height)) * tan_half_fov;
        return {origin, normalize(forward + right * sx + up * sy)};
    }
};

}  // namespace rtlab
