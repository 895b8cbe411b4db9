// Integer grid: the `intgrid` mesh (closed cube surface on the integer lattice, SF 3: [-4, 4]^3,
// 768 triangles) hit by axis-aligned rays whose origins lie on the grid lines, so each ray passes
// exactly through shared edges (one transverse coordinate an integer), vertices (both) or square
// diagonals (the shared edge of a square's two triangles). Half start inside the cube, half outside
// aimed at it: every ray must hit. Every triangle method x structure x robust on/off.
#include "datasets_gen/generators.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"

#include <cmath>
#include <string>

namespace rtlab::stab {

namespace {

/// Axis-aligned rays through the lattice of a closed cube [-h, h]^3 (h a power of two).
std::vector<Rayf> lattice_rays(float h, std::size_t count, std::uint64_t seed) {
    Sampler rng(seed, 202);
    const int n = static_cast<int>(h);
    // A lattice coordinate strictly inside (-h, h), so the ray does not run inside a cube face.
    const auto lattice = [&] {
        return static_cast<float>(static_cast<int>(rng.index(2 * n - 1)) - n + 1);
    };
    const auto anywhere = [&] { return static_cast<float>(rng.uniform(-h, h)) * 0.999f; };
    std::vector<Rayf> rays;
    rays.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t axis = rng.index(3);
        const std::size_t a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        Vec3f org;
        switch (i % 3) {
        case 0:  // through vertices
            org[a1] = lattice();
            org[a2] = lattice();
            break;
        case 1:  // along a lattice line: through edges
            org[a1] = lattice();
            org[a2] = anywhere();
            if (rng.index(2) == 0) {
                std::swap(org[a1], org[a2]);
            }
            break;
        default: {  // through a point of a square's diagonal (either diagonal)
            const float s = static_cast<float>(rng.index(64)) / 64.0f;
            const float x = lattice() + (rng.index(2) == 0 ? s : -s);
            org[a1] = x;
            const float y = lattice();
            org[a2] = rng.index(2) == 0 ? y + s : y + 1.0f - s;
            if (std::abs(org[a2]) >= h) {
                org[a2] = y;
            }
            break;
        }
        }
        const float sign = rng.index(2) == 0 ? 1.0f : -1.0f;
        Vec3f dir;
        // Half the lengths are powers of two, half not: with a power of two every operation of
        // most methods is exact on the lattice, with other lengths the reciprocals round.
        dir[axis] = sign * (i % 4 < 2 ? std::ldexp(1.0f, static_cast<int>(rng.index(5)) - 2)
                                      : static_cast<float>(rng.uniform(0.3, 3)));
        if (i % 2 == 0) {
            org[axis] = anywhere();  // inside
        } else {
            org[axis] = -sign * (h + 1.0f + static_cast<float>(rng.uniform(0, h)));  // outside
        }
        rays.push_back({org, dir});
    }
    return rays;
}

}  // namespace

std::vector<Row> run_intgrid(const Options& opt) {
    return run_intgrid(opt, Selection{});
}

std::vector<Row> run_intgrid(const Options& opt, const Selection& sel) {
    gen::GenOptions g;
    g.size = 3;
    const std::vector<Scene> scenes{gen::generate("intgrid", g)};
    const float h = scenes[0].meshes[0].mesh.bounds().hi.x;
    const std::vector<Rayf> rays = lattice_rays(h, opt.rays, opt.seed);
    return leak_rows(
        "intgrid", scenes, [&](std::size_t, const SceneTracer&) { return rays; }, sel);
}

}  // namespace rtlab::stab
