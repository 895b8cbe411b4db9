#pragma once
// False colours for per-pixel traversal cost, and the legend bar drawn into the image: the ramp,
// tick marks with their values (nodes + primitive tests per pixel) and a caption, in a 3x5 pixel
// font.

#include "intersect/vec.h"
#include "render/image.h"

#include <string>
#include <vector>

namespace rtlab {

/// Colour of t in [0, 1] (clamped) on a blue - cyan - green - yellow - red ramp.
Vec3f false_colour(float t);

/// Tick marks of the legend: at 0, 1/4, 1/2, 3/4 and 1 of the ramp.
inline constexpr int heatmap_ticks = 5;

/// The numbers printed under the ticks for a ramp from lo to hi: whole numbers when the range is
/// 20 or more (or the ticks fall on integers), else one decimal.
std::vector<std::string> heatmap_tick_labels(double lo, double hi);

/// Where the legend goes in a width x height image: the bottom `rows` rows are a one-pixel black
/// separator, `ramp` rows of the colour ramp and (when `labels`: images of 64 x 64 or more) the
/// tick values and the caption "NODES + TESTS PER PIXEL" in white on black, font pixels `scale`
/// image pixels wide.
struct HeatmapLegend {
    int rows = 0;
    int ramp = 0;
    int scale = 1;
    bool labels = false;
};
HeatmapLegend heatmap_legend(int width, int height);

/// Replaces every pixel's cost (stored in .x) by false_colour((cost - lo) / (hi - lo)) (0 when
/// hi == lo), then draws the legend (heatmap_legend) over the bottom rows: the ramp runs from lo
/// at the left edge to hi at the right edge.
void colour_heatmap(Image& img, double lo, double hi);

}  // namespace rtlab
