// False-colour ramp and legend for the heat map AOV.
#include "render/heatmap.h"

#include <algorithm>
#include <array>
#include <cstddef>

namespace rtlab {

Vec3f false_colour(float t) {
    static constexpr std::array<Vec3f, 5> ramp{Vec3f{0, 0, 1}, Vec3f{0, 1, 1}, Vec3f{0, 1, 0},
                                               Vec3f{1, 1, 0}, Vec3f{1, 0, 0}};
    const float x = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(ramp.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(x), ramp.size() - 2);
    const float f = x - static_cast<float>(i);
    return ramp[i] * (1.0f - f) + ramp[i + 1] * f;
}

void colour_heatmap(Image& img, double lo, double hi) {
    const double range = hi - lo;
    for (Vec3f& p : img.pixels) {
        const double t = range > 0 ? (static_cast<double>(p.x) - lo) / range : 0.0;
        p = false_colour(static_cast<float>(t));
    }
    if (img.width <= 0 || img.height <= 0) {
        return;
    }
    const int bar = std::min(img.height, std::max(4, img.height / 16));
    for (int y = img.height - bar; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const float t =
                img.width > 1 ? static_cast<float>(x) / static_cast<float>(img.width - 1) : 0.0f;
            img.at(x, y) = y == img.height - bar ? Vec3f{0, 0, 0} : false_colour(t);
        }
    }
}

}  // namespace rtlab
