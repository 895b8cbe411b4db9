// False-colour ramp and legend for the heat map AOV; the legend's numbers and caption are drawn
// with a 3x5 pixel font of our own (no font library needed).
#include "render/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <string_view>

namespace rtlab {

namespace {

/// One glyph: 5 rows of 3 bits, the high bit the leftmost pixel.
struct Glyph {
    char c;
    std::array<std::uint8_t, 5> rows;
};

constexpr std::array<Glyph, 26> font{{
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'+', {0, 2, 7, 2, 0}},
    {'-', {0, 0, 7, 0, 0}}, {'/', {1, 1, 2, 4, 4}}, {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}},
    {'I', {7, 2, 2, 2, 7}}, {'L', {4, 4, 4, 4, 7}}, {'N', {5, 7, 7, 5, 5}}, {'O', {2, 5, 5, 5, 2}},
    {'P', {6, 5, 6, 4, 4}}, {'R', {6, 5, 6, 5, 5}}, {'S', {3, 4, 2, 1, 6}}, {'T', {7, 2, 2, 2, 2}},
    {'X', {5, 5, 2, 5, 5}}, {' ', {0, 0, 0, 0, 0}},
}};

/// The glyph of c (upper-cased), or nullptr when the font lacks it.
const Glyph* glyph(char c) {
    if (c >= 'a' && c <= 'z') {
        c = static_cast<char>(c - 'a' + 'A');
    }
    for (const Glyph& g : font) {
        if (g.c == c) {
            return &g;
        }
    }
    return nullptr;
}

/// Draws text with its top-left corner at (x, y), each font pixel an s x s block, clipped.
void draw_text(Image& img, std::string_view text, int x, int y, int s, Vec3f colour) {
    for (const char c : text) {
        if (const Glyph* g = glyph(c)) {
            for (int row = 0; row < 5; ++row) {
                for (int col = 0; col < 3; ++col) {
                    if (((g->rows[static_cast<std::size_t>(row)] >> (2 - col)) & 1) == 0) {
                        continue;
                    }
                    for (int dy = 0; dy < s; ++dy) {
                        for (int dx = 0; dx < s; ++dx) {
                            const int px = x + col * s + dx;
                            const int py = y + row * s + dy;
                            if (px >= 0 && px < img.width && py >= 0 && py < img.height) {
                                img.at(px, py) = colour;
                            }
                        }
                    }
                }
            }
        }
        x += 4 * s;
    }
}

int text_width(std::string_view text, int s) {
    return text.empty() ? 0 : static_cast<int>(text.size()) * 4 * s - s;
}

}  // namespace

Vec3f false_colour(float t) {
    static constexpr std::array<Vec3f, 5> ramp{Vec3f{0, 0, 1}, Vec3f{0, 1, 1}, Vec3f{0, 1, 0},
                                               Vec3f{1, 1, 0}, Vec3f{1, 0, 0}};
    const float x = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(ramp.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(x), ramp.size() - 2);
    const float f = x - static_cast<float>(i);
    return ramp[i] * (1.0f - f) + ramp[i + 1] * f;
}

std::vector<std::string> heatmap_tick_labels(double lo, double hi) {
    std::vector<std::string> out;
    const bool whole = hi - lo >= 20 || (lo == std::floor(lo) && hi == std::floor(hi) &&
                                         std::fmod(hi - lo, 4.0) == 0);
    for (int i = 0; i < heatmap_ticks; ++i) {
        const double v = lo + (hi - lo) * i / (heatmap_ticks - 1);
        out.push_back(whole ? fmt::format("{:.0f}", v) : fmt::format("{:.1f}", v));
    }
    return out;
}

HeatmapLegend heatmap_legend(int width, int height) {
    HeatmapLegend l;
    l.ramp = std::min(height, std::max(4, height / 24));
    l.scale = std::max(1, std::min(width, height) / 256);
    l.labels = width >= 64 && height >= 64;
    l.rows = std::min(height, 1 + l.ramp + (l.labels ? 14 * l.scale + 2 : 0));
    return l;
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
    const HeatmapLegend l = heatmap_legend(img.width, img.height);
    const int top = img.height - l.rows;
    for (int y = top; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const float t =
                img.width > 1 ? static_cast<float>(x) / static_cast<float>(img.width - 1) : 0.0f;
            const bool ramp = y > top && y <= top + l.ramp;
            img.at(x, y) = ramp ? false_colour(t) : Vec3f{0, 0, 0};
        }
    }
    if (!l.labels) {
        return;
    }
    // Numbers under tick marks at 0, 1/4, ..., 1 of the ramp; the caption below them.
    const int s = l.scale;
    const Vec3f white{1, 1, 1};
    const std::vector<std::string> ticks = heatmap_tick_labels(lo, hi);
    const int text_y = top + 1 + l.ramp + 2 * s;
    for (int i = 0; i < heatmap_ticks; ++i) {
        const int cx = (img.width - 1) * i / (heatmap_ticks - 1);
        for (int y = top + 1 + l.ramp; y < top + 1 + l.ramp + s; ++y) {
            for (int x = std::max(0, cx - s / 2); x <= std::min(img.width - 1, cx + s / 2); ++x) {
                img.at(x, y) = white;
            }
        }
        const int w = text_width(ticks[static_cast<std::size_t>(i)], s);
        const int x = std::clamp(cx - w / 2, 1, std::max(1, img.width - w - 1));
        draw_text(img, ticks[static_cast<std::size_t>(i)], x, text_y, s, white);
    }
    constexpr std::string_view caption = "NODES + TESTS PER PIXEL";
    draw_text(img, caption, (img.width - text_width(caption, s)) / 2, text_y + 7 * s, s, white);
}

}  // namespace rtlab
