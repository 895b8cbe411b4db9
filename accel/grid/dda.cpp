// Woo's resolution rule, shared by the grid builders.
#include "accel/grid/dda.h"

#include <algorithm>
#include <cmath>

namespace rtlab {

std::array<std::uint32_t, 3> woo_resolution(const Bounds3f& box,
                                            std::size_t n,
                                            double density,
                                            std::uint32_t max_res) {
    const Vec3f d = box.diagonal();
    double volume = 1.0;
    int dims = 0;
    for (std::size_t a = 0; a < 3; ++a) {
        if (d[a] > 0.0f) {
            volume *= static_cast<double>(d[a]);
            ++dims;
        }
    }
    std::array<std::uint32_t, 3> res{1, 1, 1};
    if (dims == 0) {
        return res;
    }
    const double cells = std::max(1.0, density * static_cast<double>(n));
    const double scale = std::pow(cells / volume, 1.0 / dims);
    const double most = static_cast<double>(std::max<std::uint32_t>(max_res, 1));
    for (std::size_t a = 0; a < 3; ++a) {
        if (d[a] > 0.0f) {
            const double r = std::floor(static_cast<double>(d[a]) * scale + 0.5);
            res[a] = static_cast<std::uint32_t>(std::clamp(r, 1.0, most));
        }
    }
    return res;
}

}  // namespace rtlab
