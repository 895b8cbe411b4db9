// rtlab rays: writes a deterministic ray set for a scene (primary, shadow, diffuse, random) as a
// raw little-endian float32 file of 32-byte records.
#include "apps/commands.h"
#include "base/atomic_file.h"
#include "datasets_gen/memory_guard.h"
#include "scene/scene_io.h"
#include "trace/binary_io.h"
#include "trace/ray_gen.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace rtlab::app {

namespace {
struct RaysArgs {
    std::string scene;
    std::string kind = "primary";
    std::size_t count = 65536;
    std::uint64_t seed = 1;
    std::string out;
    std::uint64_t max_memory_mib = 0;
};

/// Peak bytes per ray: the ray vector (32; the file is written in chunks); secondary kinds also
/// hold twice as many primary rays and their hits while searching for surface points
/// (2 x (32 + 16)).
std::uint64_t bytes_per_ray(RayKind kind) {
    return kind == RayKind::shadow || kind == RayKind::diffuse ? 128 : 32;
}
}  // namespace

Command add_rays(CLI::App& root) {
    auto a = std::make_shared<RaysArgs>();
    CLI::App* sub = root.add_subcommand(
        "rays",
        "Write a ray set for a scene: records of 8 little-endian float32 "
        "(ox oy oz dx dy dz tmin tmax), deterministic for scene, kind, count and seed");
    sub->add_option("scene,--scene", a->scene,
                    "Scene JSON or mesh file (.obj .ply .off .stl), positional or --scene")
        ->required();
    sub->add_option("--kind", a->kind, "primary | shadow | diffuse | random (default primary)")
        ->check(CLI::IsMember({"primary", "shadow", "diffuse", "random"}));
    sub->add_option("--count", a->count, "Number of rays (default 65536)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
    sub->add_option("--seed", a->seed, "Seed (default 1)");
    sub->add_option("-o,--output", a->out,
                    "Ray file to write: a new file or rtlab's own earlier output (a FIFO or "
                    "device is written into; other files and links are refused)")
        ->required();
    sub->add_option("--max-memory", a->max_memory_mib,
                    "Refuse counts whose estimate exceeds this many MiB (default half of RAM)");
    return {sub, [a] {
                const RayKind kind = parse_ray_kind(a->kind);
                gen::check_memory(fmt::format("rays --count {}", a->count),
                                  gen::saturating_mul(a->count, bytes_per_ray(kind)),
                                  gen::memory_limit_mib(a->max_memory_mib));
                check_output_path(a->out);
                const Scene scene = load_scene(a->scene);
                const std::vector<Rayf> rays = make_rays(scene, kind, a->count, a->seed);
                save_rays(a->out, rays);
                std::cerr << fmt::format("rtlab rays: wrote {} {} rays to {}\n", rays.size(),
                                         a->kind, a->out);
                return 0;
            }};
}

}  // namespace rtlab::app
