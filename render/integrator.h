#pragma once
// The recursive Whitted integrator (seed 004's RT_intersect/RT_shade) run breadth first: all rays
// of one depth of one tile form a batch for SceneTracer, shading spawns the next depth's batch and
// the shadow batch. Compiled per feature set: code for a feature that is off is not generated.
// Epsilon policy: none of its own. Every secondary ray starts at offset_origin (trace/offset.h,
// the policy chosen per render) with tmin = 0; shadow rays to point lights end at the light
// (tmax = distance), to directional lights at +inf. Cost per hit: one surface_at, one shadow ray
// per light facing the surface, at most one reflected and one refracted ray.
// Internal to render/ (included by renderer.cpp only).

#include "render/optics.h"
#include "render/renderer.h"
#include "render/texture.h"
#include "trace/offset.h"
#include "trace/scene_tracer.h"
#include "trace/surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace rtlab::detail {

/// Most glass surfaces a shadow ray is followed through before it counts as blocked.
inline constexpr int max_shadow_crossings = 16;

/// What the integrator reads: the scene, its tracer and the per-render choices.
struct TraceContext {
    const Scene& scene;
    const SceneTracer& tracer;
    const std::vector<std::uint32_t>& base;             ///< primitive_id_base(scene)
    const std::vector<std::uint32_t>& object_material;  ///< material of each object in order
    FresnelForm fresnel = FresnelForm::exact;
    OffsetPolicy offset = OffsetPolicy::ulp;
    float epsilon = 1e-4f;
    int max_depth = 5;
};

/// Kind of a closest-hit ray (for the statistics).
enum class PathKind : std::uint8_t { eye, reflected, refracted };

/// A ray of the ray tree with the weight its radiance contributes to accumulator `slot`.
struct Path {
    Rayf ray;            ///< unit direction, so hit t is a distance
    Vec3f weight;        ///< product of the k_r / k_t / Fresnel / absorption factors so far
    std::uint32_t slot;  ///< accumulator index
    float lambda_nm;     ///< wavelength in spectral mode, 0 otherwise
    int depth;           ///< 0 for eye rays
    PathKind kind;
};

/// A shadow ray carrying the light it lets through when unblocked.
struct ShadowPath {
    Rayf ray;
    Vec3f contribution;
    std::uint32_t slot;
};

/// Material of the object holding global primitive `prim`.
inline const Material& material_of(const TraceContext& c, std::uint32_t prim) {
    return c.scene.materials[c.object_material[locate_primitive(c.base, prim).object]];
}

/// Boxes and oriented boxes are solids to their intersection methods: a ray starting inside one
/// hits it at t = tmin. A refracted or shadow ray inside a glass box needs the far side, so such a
/// hit becomes the ray's exit from the box (slab far distance; only the winning hit is changed,
/// so other objects inside the box are not seen). Other primitive types report surfaces already.
inline void exit_solid(const TraceContext& c, Hit& hit, const Rayf& ray) {
    if (!hit.valid() || hit.t > ray.tmin) {
        return;
    }
    const ObjectRef o = c.scene.order[locate_primitive(c.base, hit.prim).object];
    Vec3f org = ray.org;
    Vec3f dir = ray.dir;
    // The solid's box in its own frame, with org and dir moved into it; nullopt for non-solids.
    const std::optional<Bounds3f> box =
        visit_object(c.scene, o, [&]<class P>(const auto& obj) -> std::optional<Bounds3f> {
            if constexpr (requires { P::solid_frame(obj, org, dir); }) {
                return P::solid_frame(obj, org, dir);
            } else {
                return std::nullopt;
            }
        });
    if (!box) {
        return;
    }
    const Vec3f lo = box->lo;
    const Vec3f hi = box->hi;
    float t_far = ray.tmax;
    for (std::size_t a = 0; a < 3; ++a) {
        const float inv = 1.0f / dir[a];
        const float t0 = (lo[a] - org[a]) * inv;
        const float t1 = (hi[a] - org[a]) * inv;
        t_far = std::min(t_far, std::max(t0, t1));  // NaN (0 * inf) is ignored by min
    }
    if (t_far > ray.tmin && std::isfinite(t_far)) {
        hit.t = t_far;
    }
}

/// Adds v to accumulator `slot`.
inline void add(std::span<Vec3f> accum, std::uint32_t slot, const Vec3f& v) {
    accum[slot] += v;
}

/// Resolves a shadow batch: unblocked rays add their contribution. With Refraction, every blocked
/// ray is walked surface by surface (closest hits), multiplying by each crossed material's k_t (no
/// refraction, Fresnel or absorption on shadow rays: seed 004's "how much light opaque and
/// transparent surfaces block", kept simple) until the light or an opaque surface is reached. The
/// any-hit blocker's own material does not decide: which blocker an any-hit query meets first
/// depends on the structure, and a walk's offset origin can step past an opaque surface touching a
/// glass one (a flake's spheres touch), so deciding by it made images differ between structures.
template <bool Refraction>
void resolve_shadows(const TraceContext& c,
                     std::vector<ShadowPath>& shadows,
                     std::span<Vec3f> accum,
                     RenderStats& st) {
    std::vector<Rayf> rays(shadows.size());
    for (std::size_t i = 0; i < shadows.size(); ++i) {
        rays[i] = shadows[i].ray;
    }
    std::vector<std::uint32_t> blocker(shadows.size());
    c.tracer.occluded(rays, blocker);
    st.shadow += shadows.size();
    std::vector<ShadowPath> walk;
    for (std::size_t i = 0; i < shadows.size(); ++i) {
        if (blocker[i] == invalid_id) {
            add(accum, shadows[i].slot, shadows[i].contribution);
        } else if constexpr (Refraction) {
            walk.push_back(shadows[i]);
        }
    }
    if constexpr (Refraction) {
        std::vector<Hit> hits;
        std::vector<ShadowPath> next;
        for (int crossing = 0; crossing < max_shadow_crossings && !walk.empty(); ++crossing) {
            rays.resize(walk.size());
            hits.resize(walk.size());
            for (std::size_t i = 0; i < walk.size(); ++i) {
                rays[i] = walk[i].ray;
            }
            c.tracer.intersect(rays, hits);
            for (std::size_t i = 0; i < walk.size(); ++i) {
                exit_solid(c, hits[i], rays[i]);
            }
            if (crossing > 0) {
                st.shadow += walk.size();
            }
            next.clear();
            for (std::size_t i = 0; i < walk.size(); ++i) {
                if (!hits[i].valid()) {
                    add(accum, walk[i].slot, walk[i].contribution);
                    continue;
                }
                const Material& m = material_of(c, hits[i].prim);
                if (m.transmit <= 0) {
                    continue;
                }
                const SurfacePoint sp = surface_at(c.scene, c.base, hits[i], rays[i]);
                ShadowPath s = walk[i];
                s.contribution = s.contribution * m.transmit;
                s.ray.org = offset_origin(sp.p, -sp.n, c.offset, c.epsilon);
                s.ray.tmin = 0;
                s.ray.tmax = rays[i].tmax - hits[i].t;
                if (s.ray.tmax > 0) {
                    next.push_back(s);
                } else {
                    add(accum, s.slot, s.contribution);
                }
            }
            walk.swap(next);
        }
    }
}

/// The direct light at hit sp of `path` (material m, surface colour `color`, path weight w): per
/// light that the surface faces, the diffuse and specular term as a shadow ray to resolve.
inline void light_shadow_rays(const TraceContext& c,
                              const Path& path,
                              const SurfacePoint& sp,
                              const Material& m,
                              const Vec3f& color,
                              const Vec3f& w,
                              std::vector<ShadowPath>& shadows) {
    const Vec3f view = -path.ray.dir;
    const Vec3f org = offset_origin(sp.p, sp.n, c.offset, c.epsilon);
    for (const Light& light : c.scene.lights) {
        Vec3f to_light = light.position;
        float dist = std::numeric_limits<float>::infinity();
        if (light.kind == LightKind::point) {
            to_light = light.position - org;
            dist = length(to_light);
            if (!(dist > 0)) {
                continue;
            }
        }
        const Vec3f l = normalize(to_light);
        const float n_dot_l = dot(sp.n, l);
        if (n_dot_l <= 0) {
            continue;  // the surface faces away: no shadow ray
        }
        Vec3f term = color * (m.diffuse * n_dot_l);
        if (m.specular > 0) {
            const float r_dot_v = dot(reflect(-l, sp.n), view);
            if (r_dot_v > 0) {
                const float s = m.specular * std::pow(r_dot_v, m.shininess);
                term += Vec3f{s, s, s};
            }
        }
        const Vec3f contribution = w * light.color * term;
        if (max_component(contribution) <= 0) {
            continue;
        }
        shadows.push_back({Rayf{org, l, 0.0f, dist}, contribution, path.slot});
    }
}

/// The mirror ray (and with Refraction the refracted one) that `path` spawns at hit sp of
/// material m with path weight w, weighted as trace_paths describes; none at c.max_depth.
template <bool Refraction>
void secondary_rays(const TraceContext& c,
                    const Path& path,
                    const SurfacePoint& sp,
                    const Material& m,
                    const Vec3f& w,
                    std::vector<Path>& next) {
    if (path.depth >= c.max_depth) {
        return;
    }
    const Vec3f d = path.ray.dir;
    const float cos_i = std::min(1.0f, -dot(d, sp.n));
    float w_r = m.reflect;
    float w_t = 0;
    std::optional<Vec3f> t_dir;
    float ior = m.ior;
    if constexpr (Refraction) {
        if (m.transmit > 0) {
            if (path.lambda_nm > 0 && m.dispersion > 0) {
                ior = cauchy_ior(m.ior, m.dispersion, path.lambda_nm);
            }
            const float eta_i = sp.front_face ? 1.0f : ior;
            const float eta_t = sp.front_face ? ior : 1.0f;
            t_dir = refract(d, sp.n, eta_i / eta_t);
            if (m.fresnel) {
                const float r = fresnel(c.fresnel, cos_i, eta_i, eta_t);
                w_r = m.reflect + m.transmit * r;
                w_t = t_dir ? m.transmit * (1.0f - r) : 0.0f;
            } else {
                w_t = t_dir ? m.transmit : 0.0f;
            }
        }
    }
    if (m.fresnel && m.transmit <= 0 && w_r > 0) {
        w_r *= fresnel(c.fresnel, cos_i, 1.0f, ior);
    }
    if (w_r > 0) {
        const Rayf r{offset_origin(sp.p, sp.n, c.offset, c.epsilon), normalize(reflect(d, sp.n))};
        next.push_back(
            {r, w * w_r, path.slot, path.lambda_nm, path.depth + 1, PathKind::reflected});
    }
    if constexpr (Refraction) {
        if (w_t > 0 && t_dir) {
            const Rayf r{offset_origin(sp.p, -sp.n, c.offset, c.epsilon), normalize(*t_dir)};
            next.push_back(
                {r, w * w_t, path.slot, path.lambda_nm, path.depth + 1, PathKind::refracted});
        }
    }
}

/// Traces `paths` and everything they spawn, adding radiance to `accum`. Shadows: lights exist
/// (diffuse and specular terms, shadow rays). Reflection: mirror rays (also compiled when
/// Refraction is on, for Fresnel reflection and total internal reflection). Refraction: Snell
/// rays with Fresnel weights, Beer-Lambert absorption and wavelength-dependent indices.
/// Textures: checker lookups (plain colours otherwise).
///
/// Weights at a hit with material m (R = Fresnel reflectance for the chosen form, cos_i between
/// the ray and the facing normal, indices 1 outside and n inside, entering when front_face):
///   m.fresnel off: reflected k_r, transmitted k_t (0 under total internal reflection, seed 004);
///   m.fresnel on, k_t > 0: reflected k_r + k_t R, transmitted k_t (1 - R) (R = 1 under TIR);
///   m.fresnel on, k_t = 0: reflected k_r R with R for air into m.ior (a dielectric coat).
/// A ray that hits the back face of a transmitting material travelled inside it: its weight is
/// multiplied by exp(-absorption * t) per channel.
template <bool Shadows, bool Reflection, bool Refraction, bool Textures>
void trace_paths(const TraceContext& c,
                 std::vector<Path> paths,
                 std::span<Vec3f> accum,
                 RenderStats& st) {
    constexpr bool Reflect = Reflection || Refraction;
    const Scene& scene = c.scene;
    std::vector<Rayf> rays;
    std::vector<Hit> hits;
    std::vector<Path> next;
    std::vector<ShadowPath> shadows;
    while (!paths.empty()) {
        rays.resize(paths.size());
        hits.resize(paths.size());
        for (std::size_t i = 0; i < paths.size(); ++i) {
            rays[i] = paths[i].ray;
            switch (paths[i].kind) {
            case PathKind::eye:
                ++st.eye;
                break;
            case PathKind::reflected:
                ++st.reflected;
                break;
            case PathKind::refracted:
                ++st.refracted;
                break;
            }
        }
        c.tracer.intersect(rays, hits);
        if constexpr (Refraction) {
            for (std::size_t i = 0; i < paths.size(); ++i) {
                exit_solid(c, hits[i], rays[i]);
            }
        }
        next.clear();
        shadows.clear();
        for (std::size_t i = 0; i < paths.size(); ++i) {
            const Path& path = paths[i];
            if (!hits[i].valid()) {
                add(accum, path.slot, path.weight * scene.background);
                continue;
            }
            ++st.hits;
            const SurfacePoint sp = surface_at(scene, c.base, hits[i], path.ray);
            const Material& m = scene.materials[sp.material];
            Vec3f w = path.weight;
            if constexpr (Refraction) {
                if (!sp.front_face && m.transmit > 0) {
                    w = w * beer_lambert(m.absorption, hits[i].t);
                }
            }
            Vec3f color = m.color;
            if constexpr (Textures) {
                color = surface_color(m, sp.p);
            }
            add(accum, path.slot, w * color * m.ambient);

            if constexpr (Shadows) {
                light_shadow_rays(c, path, sp, m, color, w, shadows);
            }
            if constexpr (Reflect) {
                secondary_rays<Refraction>(c, path, sp, m, w, next);
            }
        }
        if constexpr (Shadows) {
            if (!shadows.empty()) {
                resolve_shadows<Refraction>(c, shadows, accum, st);
            }
        }
        paths.swap(next);
    }
}

}  // namespace rtlab::detail
