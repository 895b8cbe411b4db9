// Ray-set generators (see ray_gen.h for the definitions and the offset policy).
#include "trace/ray_gen.h"

#include "base/error.h"
#include "trace/camera.h"
#include "trace/scene_tracer.h"
#include "trace/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace rtlab {

namespace {

// Uniform float in [0, 1) from the top 24 bits: the same on every platform (unlike
// std::uniform_real_distribution, whose algorithm the standard leaves open).
float u01(std::mt19937_64& rng) {
    return static_cast<float>(rng() >> 40) * 0x1.0p-24f;
}

Vec3f uniform_sphere(std::mt19937_64& rng) {
    const float z = 1.0f - 2.0f * u01(rng);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * std::numbers::pi_v<float> * u01(rng);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Cosine-distributed direction about unit n (Malley's method over an orthonormal basis).
Vec3f cosine_hemisphere(const Vec3f& n, std::mt19937_64& rng) {
    const Vec3f a = std::abs(n.x) > 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0};
    const Vec3f t = normalize(cross(a, n));
    const Vec3f b = cross(n, t);
    const float r = std::sqrt(u01(rng));
    const float phi = 2.0f * std::numbers::pi_v<float> * u01(rng);
    const float x = r * std::cos(phi), y = r * std::sin(phi);
    const float z = std::sqrt(std::max(0.0f, 1.0f - x * x - y * y));
    return normalize(t * x + b * y + n * z);
}

Vec3f point_in(const Bounds3f& b, std::mt19937_64& rng) {
    const Vec3f d = b.diagonal();
    return {b.lo.x + d.x * u01(rng), b.lo.y + d.y * u01(rng), b.lo.z + d.z * u01(rng)};
}

std::vector<Rayf> primary_rays(const Scene& scene, std::size_t count, std::mt19937_64& rng) {
    const CameraFrame cam(scene.camera);
    const int w = scene.camera.width, h = scene.camera.height;
    std::vector<Rayf> rays(count);
    for (Rayf& r : rays) {
        const float px = u01(rng) * static_cast<float>(w);
        const float py = u01(rng) * static_cast<float>(h);
        r = cam.ray(px, py, w, h);
    }
    return rays;
}

}  // namespace

std::string_view to_string(RayKind k) {
    switch (k) {
    case RayKind::primary:
        return "primary";
    case RayKind::shadow:
        return "shadow";
    case RayKind::diffuse:
        return "diffuse";
    case RayKind::random:
        return "random";
    }
    return "?";
}

RayKind parse_ray_kind(std::string_view name) {
    for (RayKind k : {RayKind::primary, RayKind::shadow, RayKind::diffuse, RayKind::random}) {
        if (to_string(k) == name) {
            return k;
        }
    }
    throw std::invalid_argument("unknown ray kind '" + std::string(name) +
                                "' (primary, shadow, diffuse, random)");
}

std::vector<Rayf> make_rays(const Scene& scene,
                            RayKind kind,
                            std::size_t count,
                            std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const Bounds3f box = scene_bounds(scene);
    if (box.empty()) {
        throw Error("scene has no objects to aim rays at");
    }
    if (kind == RayKind::primary) {
        return primary_rays(scene, count, rng);
    }
    if (kind == RayKind::random) {
        const Vec3f grow = box.diagonal() * 0.05f;
        const Bounds3f big{box.lo - grow, box.hi + grow};
        std::vector<Rayf> rays(count);
        for (Rayf& r : rays) {
            r.org = point_in(big, rng);
            r.dir = uniform_sphere(rng);
        }
        return rays;
    }

    // Secondary rays start where primary rays hit, traced with the default structure, robust.
    const SceneTracer tracer(scene, TraceSetup{parse_accel_spec(default_accel), {}, true});
    const std::vector<std::uint32_t> base = primitive_id_base(scene);
    const float diag = length(box.diagonal());
    std::vector<Rayf> out;
    out.reserve(count);
    std::size_t batches = 0;
    while (out.size() < count) {
        const std::size_t want = std::max<std::size_t>(1024, (count - out.size()) * 2);
        const std::vector<Rayf> prim = primary_rays(scene, want, rng);
        std::vector<Hit> hits(prim.size());
        tracer.intersect(prim, hits);
        for (std::size_t i = 0; i < prim.size() && out.size() < count; ++i) {
            if (!hits[i].valid()) {
                continue;
            }
            const SurfacePoint sp = surface_at(scene, base, hits[i], prim[i]);
            const float scale =
                std::max(std::abs(sp.p.x), std::max(std::abs(sp.p.y), std::abs(sp.p.z)));
            const float offset =
                std::max(1e-5f * diag, 64.0f * std::numeric_limits<float>::epsilon() * scale);
            Rayf r;
            if (kind == RayKind::diffuse) {
                r.org = sp.p + sp.n * offset;
                r.dir = cosine_hemisphere(sp.n, rng);
            } else {
                Vec3f target;
                bool directional = false;
                if (scene.lights.empty()) {
                    target = point_in(box, rng);
                } else {
                    const Light& l = scene.lights[rng() % scene.lights.size()];
                    directional = l.kind == LightKind::directional;
                    target = l.position;
                }
                // Leave on the side facing the target, so the ray does not start inside.
                const Vec3f towards = directional ? target : target - sp.p;
                const Vec3f n = dot(towards, sp.n) >= 0 ? sp.n : -sp.n;
                r.org = sp.p + n * offset;
                r.dir = directional ? target : target - r.org;
                r.tmax = directional ? std::numeric_limits<float>::infinity() : 1.0f;
                if (!is_valid(r)) {
                    continue;
                }
            }
            out.push_back(r);
        }
        if (++batches == 4 && out.empty()) {
            throw Error("primary rays hit nothing: cannot start " + std::string(to_string(kind)) +
                        " rays (is the camera looking at the scene?)");
        }
    }
    return out;
}

}  // namespace rtlab
