#pragma once
// False colours for per-pixel traversal cost, and the legend bar drawn into the image.

#include "intersect/vec.h"
#include "render/image.h"

namespace rtlab {

/// Colour of t in [0, 1] (clamped) on a blue - cyan - green - yellow - red ramp.
Vec3f false_colour(float t);

/// Replaces every pixel's cost (stored in .x) by false_colour((cost - lo) / (hi - lo)) (0 when
/// hi == lo), then draws the legend: the bottom rows (max(4, height / 16)) become the ramp from lo
/// at the left edge to hi at the right edge, under a one-pixel black separator.
void colour_heatmap(Image& img, double lo, double hi);

}  // namespace rtlab
