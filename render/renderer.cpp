// The renderer: feature plan and explanation, the table of integrator instances, tiles in
// parallel (each tile a sequence of batches, so results do not depend on scheduling), AOVs and
// the SPD corner mode.
#include "render/renderer.h"

#include "render/heatmap.h"
#include "render/integrator.h"
#include "trace/camera.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <utility>

namespace rtlab {

namespace {

using detail::Path;
using detail::PathKind;
using detail::TraceContext;

// One integrator instance; index bits: 1 shadows, 2 reflection, 4 refraction, 8 textures.
using TraceFn = void (*)(const TraceContext&, std::vector<Path>, std::span<Vec3f>, RenderStats&);

// Refraction compiles reflection rays in any case, so those entries share one instance (12 in
// all).
template <std::size_t I>
constexpr TraceFn instance() {
    constexpr std::size_t j = (I & 4) != 0 ? (I | 2) : I;
    return &detail::trace_paths<(j & 1) != 0, (j & 2) != 0, (j & 4) != 0, (j & 8) != 0>;
}

template <std::size_t... I>
constexpr std::array<TraceFn, sizeof...(I)> make_table(std::index_sequence<I...>) {
    return {instance<I>()...};
}

constexpr std::array<TraceFn, 16> trace_table = make_table(std::make_index_sequence<16>{});

// Materials used by objects, in material order.
std::vector<bool> used_materials(const Scene& s) {
    std::vector<bool> used(s.materials.size(), false);
    for_each_type<PrimTypes>([&]<class P>() {
        for (const auto& o : P::objects(s)) {
            used[o.material] = true;
        }
    });
    return used;
}

// "material 'glass' (transmit 0.9)" for the first used material satisfying pred, or empty.
template <class Pred>
std::string first_material(const Scene& s, const std::vector<bool>& used, Pred pred) {
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        if (used[i] && pred(s.materials[i])) {
            return "material '" + s.materials[i].name + "'";
        }
    }
    return {};
}

std::size_t object_count(const Scene& s, PrimType t) {
    return visit_prim_type(t, [&]<class P>() { return P::objects(s).size(); });
}

void check_settings(const RenderSettings& r) {
    const auto fail = [](const std::string& m) { throw std::invalid_argument(m); };
    if (r.width < 0 || r.height < 0 || r.width > 16384 || r.height > 16384) {
        fail("image size must be within 1..16384 (0 = the camera's)");
    }
    if (r.spp < 1 || r.spp > 4096) {
        fail("samples per pixel must be within 1..4096");
    }
    if (r.max_depth < 0 || r.max_depth > 64) {
        fail("max depth must be within 0..64");
    }
    if (r.wavelengths < 1 || r.wavelengths > 256) {
        fail("wavelengths must be within 1..256");
    }
    if (!(r.epsilon >= 0) || !std::isfinite(r.epsilon)) {
        fail("epsilon must be finite and >= 0");
    }
    if (r.tile < 1) {
        fail("tile size must be >= 1");
    }
}

// Radical inverse in base 2 of i (van der Corput), in [0, 1).
float radical_inverse(std::uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    return static_cast<float>(i) * 0x1p-32f;
}

// Sample offsets inside a pixel: a shifted Hammersley set, (0.5, 0.5) for one sample.
std::vector<std::pair<float, float>> pixel_offsets(int spp) {
    std::vector<std::pair<float, float>> out;
    const float n = static_cast<float>(spp);
    for (int s = 0; s < spp; ++s) {
        const float y = radical_inverse(static_cast<std::uint32_t>(s)) + 0.5f / n;
        out.emplace_back((static_cast<float>(s) + 0.5f) / n, y >= 1 ? y - 1 : y);
    }
    return out;
}

}  // namespace

std::string_view to_string(Aov a) {
    switch (a) {
    case Aov::color:
        return "color";
    case Aov::depth:
        return "depth";
    case Aov::normal:
        return "normal";
    case Aov::heatmap:
        return "heatmap";
    }
    return "?";
}

Aov parse_aov(std::string_view name) {
    for (Aov a : {Aov::color, Aov::depth, Aov::normal, Aov::heatmap}) {
        if (to_string(a) == name) {
            return a;
        }
    }
    throw std::invalid_argument("unknown AOV '" + std::string(name) +
                                "' (known: color, depth, normal, heatmap)");
}

std::string_view fresnel_name(FresnelForm f) {
    return f == FresnelForm::exact ? "exact" : "schlick";
}

FresnelForm parse_fresnel(std::string_view name) {
    if (name == "exact") {
        return FresnelForm::exact;
    }
    if (name == "schlick") {
        return FresnelForm::schlick;
    }
    throw std::invalid_argument("unknown Fresnel form '" + std::string(name) +
                                "' (known: exact, schlick)");
}

namespace {

/// One reason per primitive type: whether the scene has such objects (a structure is built).
void primitive_reasons(const Scene& s, RenderPlan& p) {
    for (std::size_t t = 0; t < prim_type_count; ++t) {
        const auto type = static_cast<PrimType>(t);
        const std::size_t n = object_count(s, type);
        p.reasons.push_back({std::string(to_string(type)), p.features.prims[t],
                             n > 0 ? std::to_string(n) + " " + std::string(to_string(type)) +
                                         " object(s): a structure is built and traversed"
                                   : "no " + std::string(to_string(type)) +
                                         " objects: no structure, no intersection code runs"});
    }
}

/// One reason per shading feature: on or off in the scene and why, and whether its code path is
/// compiled into the instance that runs.
void feature_reasons(const Scene& s, const RenderSettings& r, RenderPlan& p) {
    const SceneFeatures& f = p.features;
    const std::vector<bool> used = used_materials(s);
    const bool all = r.all_features;
    const bool colour = r.aov == Aov::color;
    // `compiled`: the code path holding this feature is in the instance that runs. Features
    // with their own template flag say why they are compiled although off; the lighter ones
    // (fresnel, absorption, dispersion) are run-time checks inside the reflection/refraction path.
    const auto add = [&](std::string name, bool on, bool compiled, bool own_flag,
                         std::string why_on, std::string why_off) {
        std::string why = on ? std::move(why_on) : std::move(why_off);
        if (!colour) {
            why += "; the " + std::string(to_string(r.aov)) + " AOV traces eye rays only";
        } else if (compiled && !on && own_flag) {
            why += all ? "; compiled in anyway (--all-features)"
                       : "; compiled in anyway (refraction reflects too: Fresnel, total "
                         "internal reflection)";
        } else if (!own_flag) {
            why += compiled ? " (run-time check inside the compiled path)"
                            : " (its path is compiled out)";
        }
        p.reasons.push_back({std::move(name), on && colour, why});
    };
    add("shadows", f.shadows, p.shadows, true,
        std::to_string(s.lights.size()) + " light(s): diffuse/specular terms and shadow rays",
        "no lights: ambient only, no shadow rays");
    add("reflection", f.reflection, p.reflection, true,
        first_material(s, used, [](const Material& m) { return m.reflect > 0; }) +
            " has reflect > 0: mirror rays",
        "no used material has reflect > 0: no mirror rays");
    add("refraction", f.refraction, p.refraction, true,
        first_material(s, used, [](const Material& m) { return m.transmit > 0; }) +
            " has transmit > 0: refraction rays, shadow rays pass through it",
        "no used material has transmit > 0: no refraction code");
    add("fresnel", f.fresnel, p.reflection, false,
        first_material(
            s, used,
            [](const Material& m) { return m.fresnel && (m.reflect > 0 || m.transmit > 0); }) +
            " has fresnel: " + std::string(fresnel_name(r.fresnel)) + " Fresnel weights",
        "no reflective/refractive material asks for fresnel: fixed k_r, k_t");
    add("absorption", f.absorption, p.refraction, false,
        first_material(
            s, used,
            [](const Material& m) { return m.transmit > 0 && max_component(m.absorption) > 0; }) +
            " absorbs: Beer-Lambert inside it",
        "no refractive material absorbs");
    std::string spectral_why;
    if (!p.spectral) {
        spectral_why =
            f.dispersion ? "; spectral mode off (--no-spectral): dispersion ignored" : "";
    } else {
        spectral_why = "; spectral mode with " + std::to_string(r.wavelengths) + " wavelengths" +
                       (r.spectral.has_value() ? " (--spectral)" : " (automatic)");
    }
    add("dispersion", f.dispersion, p.refraction, false,
        first_material(s, used,
                       [](const Material& m) { return m.transmit > 0 && m.dispersion > 0; }) +
            " has dispersion: Cauchy index per wavelength" + spectral_why,
        "no refractive material disperses" +
            (p.spectral ? std::string("; spectral mode forced (--spectral)") : std::string()));
    add("textures", f.textures, p.textures, true,
        first_material(s, used,
                       [](const Material& m) { return m.texture.kind != TextureKind::none; }) +
            " has a checker texture",
        "no used material has a texture: plain colours");
}

}  // namespace

RenderPlan plan_render(const Scene& s, const RenderSettings& r) {
    check_settings(r);
    RenderPlan p;
    p.features = features(s);
    const SceneFeatures& f = p.features;
    const bool all = r.all_features;
    const bool colour = r.aov == Aov::color;
    p.shadows = colour && (all || f.shadows);
    p.reflection = colour && (all || f.reflection || f.refraction);
    p.refraction = colour && (all || f.refraction);
    p.textures = colour && (all || f.textures);
    p.spectral = colour && p.refraction && r.spectral.value_or(f.dispersion);

    primitive_reasons(s, p);
    feature_reasons(s, r, p);
    const auto flag = [](bool on, const char* name) { return on ? std::string(name) : "-"; };
    p.instantiation = colour ? "trace_paths<" + flag(p.shadows, "shadows") + ", " +
                                   flag(p.reflection, "reflection") + ", " +
                                   flag(p.refraction, "refraction") + ", " +
                                   flag(p.textures, "textures") + ">"
                             : "eye rays only (" + std::string(to_string(r.aov)) + " AOV)";
    return p;
}

namespace {

/// Where a render's eye rays start: the image size, the sample grid (pixel corners in SPD mode,
/// else pixels with spp samples each) and the camera frame.
struct SampleGrid {
    int width;                                     ///< image
    int height;                                    ///< image
    int w;                                         ///< grid: width + 1 in SPD mode
    int h;                                         ///< grid: height + 1 in SPD mode
    std::vector<std::pair<float, float>> offsets;  ///< sample offsets within a grid point
    float inv_samples;
    CameraFrame frame;

    SampleGrid(const Camera& cam, const RenderSettings& r)
        : width(cam.width)
        , height(cam.height)
        , w(r.spd ? cam.width + 1 : cam.width)
        , h(r.spd ? cam.height + 1 : cam.height)
        , offsets(r.spd ? std::vector<std::pair<float, float>>{{0.0f, 0.0f}} : pixel_offsets(r.spp))
        , inv_samples(1.0f / static_cast<float>(offsets.size()))
        , frame(cam) {}

    Rayf eye_ray(int x, int y, const std::pair<float, float>& o) const {
        return frame.ray(static_cast<float>(x) + o.first, static_cast<float>(y) + o.second, width,
                         height);
    }
};

/// The grid points [x0, x1) x [y0, y1) of one tile; slot(x, y) indexes its accumulator.
struct TileRect {
    int x0, y0, x1, y1;
    std::size_t size() const {
        return static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0);
    }
    std::uint32_t slot(int x, int y) const {
        return static_cast<std::uint32_t>((y - y0) * (x1 - x0) + (x - x0));
    }
};

/// Aov::color: every sample of the tile (one path per wavelength in spectral mode) through the
/// integrator instance `trace`.
void colour_tile(const SampleGrid& g,
                 const TileRect& t,
                 const std::vector<SpectralSample>& spectrum,
                 const TraceContext& ctx,
                 TraceFn trace,
                 std::vector<Vec3f>& accum,
                 RenderStats& st) {
    std::vector<Path> paths;
    for (int y = t.y0; y < t.y1; ++y) {
        for (int x = t.x0; x < t.x1; ++x) {
            for (const auto& o : g.offsets) {
                const Rayf ray = g.eye_ray(x, y, o);
                if (spectrum.empty()) {
                    const Vec3f w{g.inv_samples, g.inv_samples, g.inv_samples};
                    paths.push_back({ray, w, t.slot(x, y), 0.0f, 0, PathKind::eye});
                } else {
                    for (const SpectralSample& k : spectrum) {
                        paths.push_back({ray, k.rgb_weight * g.inv_samples, t.slot(x, y),
                                         k.lambda_nm, 0, PathKind::eye});
                    }
                }
            }
        }
    }
    trace(ctx, std::move(paths), accum, st);
}

/// The other AOVs: eye rays only, each sample's value (depth: distance and hit weight, resolved
/// by resolve_aov; normal; heatmap: nodes + primitives) averaged into accum.
void aov_tile(const Scene& s,
              const SceneTracer& tracer,
              const std::vector<std::uint32_t>& base,
              Aov aov,
              const SampleGrid& g,
              const TileRect& t,
              std::vector<Vec3f>& accum,
              RenderStats& st) {
    std::vector<Rayf> rays;
    std::vector<std::uint32_t> slots;
    for (int y = t.y0; y < t.y1; ++y) {
        for (int x = t.x0; x < t.x1; ++x) {
            for (const auto& o : g.offsets) {
                rays.push_back(g.eye_ray(x, y, o));
                slots.push_back(t.slot(x, y));
            }
        }
    }
    std::vector<Hit> hits(rays.size());
    std::vector<TraversalStats> counts(rays.size());
    if (aov == Aov::heatmap) {
        tracer.intersect_counted(rays, hits, counts);
    } else {
        tracer.intersect(rays, hits);
    }
    st.eye += rays.size();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        Vec3f v{0, 0, 0};
        if (hits[i].valid()) {
            ++st.hits;
        }
        if (aov == Aov::heatmap) {
            v.x = static_cast<float>(counts[i].nodes + counts[i].prims);
        } else if (hits[i].valid()) {
            if (aov == Aov::depth) {
                v = Vec3f{hits[i].t, 1, 0};  // distance, hit weight: resolved below
            } else {
                v = surface_at(s, base, hits[i], rays[i]).n * 0.5f + Vec3f{0.5f, 0.5f, 0.5f};
            }
        }
        accum[slots[i]] += v * g.inv_samples;
    }
}

/// SPD mode: each pixel the mean of its four corners on the (width + 1) x (height + 1) grid.
Image corner_average(const Image& grid, int width, int height) {
    Image out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            out.at(x, y) =
                (grid.at(x, y) + grid.at(x + 1, y) + grid.at(x, y + 1) + grid.at(x + 1, y + 1)) *
                0.25f;
        }
    }
    return out;
}

/// Display values of the depth and heatmap AOVs from what the tiles accumulated.
void resolve_aov(Image& image, Aov aov, RenderStats& stats) {
    if (aov == Aov::depth) {
        // .x holds the weighted sum of the hit distances, .y the weight of the samples that hit:
        // the pixel's depth is their mean over the hits, depth_no_hit when no sample hit.
        for (Vec3f& p : image.pixels) {
            const float d = p.y > 0 ? p.x / p.y : depth_no_hit;
            p = Vec3f{d, d, d};
        }
    }
    if (aov == Aov::heatmap) {
        double lo = std::numeric_limits<double>::infinity();
        double hi = 0;
        for (const Vec3f& p : image.pixels) {
            lo = std::min(lo, static_cast<double>(p.x));
            hi = std::max(hi, static_cast<double>(p.x));
        }
        stats.heat_min = image.pixels.empty() ? 0.0 : lo;
        stats.heat_max = hi;
        colour_heatmap(image, stats.heat_min, stats.heat_max);
    }
}

}  // namespace

RenderResult render(const Scene& s, const SceneTracer& tracer, const RenderSettings& r) {
    RenderResult out;
    out.plan = plan_render(s, r);
    const RenderPlan& plan = out.plan;
    out.stats.build_ms = tracer.build_ms();

    Camera cam = s.camera;
    cam.width = r.width > 0 ? r.width : cam.width;
    cam.height = r.height > 0 ? r.height : cam.height;
    const SampleGrid g(cam, r);
    std::vector<SpectralSample> spectrum;
    if (plan.spectral) {
        spectrum = spectral_samples(r.wavelengths);
    }

    const std::vector<std::uint32_t> base = primitive_id_base(s);
    std::vector<std::uint32_t> materials;
    materials.reserve(s.order.size());
    for (const ObjectRef& o : s.order) {
        materials.push_back(object_material(s, o));
    }
    const TraceContext ctx{s, tracer, base, materials, r.fresnel, r.offset, r.epsilon, r.max_depth};
    const TraceFn trace = trace_table[(plan.shadows ? 1u : 0u) | (plan.reflection ? 2u : 0u) |
                                      (plan.refraction ? 4u : 0u) | (plan.textures ? 8u : 0u)];

    const int tiles_x = (g.w + r.tile - 1) / r.tile;
    const int tiles_y = (g.h + r.tile - 1) / r.tile;
    const auto tile_count = static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y);
    Image grid(g.w, g.h);
    std::vector<RenderStats> tile_stats(tile_count);
    std::atomic<std::size_t> done{0};

    const auto render_tile = [&](std::size_t i) {
        const int x0 = static_cast<int>(i % static_cast<std::size_t>(tiles_x)) * r.tile;
        const int y0 = static_cast<int>(i / static_cast<std::size_t>(tiles_x)) * r.tile;
        const TileRect t{x0, y0, std::min(g.w, x0 + r.tile), std::min(g.h, y0 + r.tile)};
        std::vector<Vec3f> accum(t.size(), Vec3f{0, 0, 0});
        if (r.aov == Aov::color) {
            colour_tile(g, t, spectrum, ctx, trace, accum, tile_stats[i]);
        } else {
            aov_tile(s, tracer, base, r.aov, g, t, accum, tile_stats[i]);
        }
        for (int y = t.y0; y < t.y1; ++y) {
            for (int x = t.x0; x < t.x1; ++x) {
                grid.at(x, y) = accum[t.slot(x, y)];
            }
        }
        const std::size_t finished = done.fetch_add(1) + 1;
        if (r.progress) {
            r.progress(finished, tile_count);
        }
    };

    const auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tile_count, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              render_tile(i);
                          }
                      });
    out.image = r.spd ? corner_average(grid, g.width, g.height) : std::move(grid);
    resolve_aov(out.image, r.aov, out.stats);
    out.stats.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    for (const RenderStats& t : tile_stats) {
        out.stats.eye += t.eye;
        out.stats.shadow += t.shadow;
        out.stats.reflected += t.reflected;
        out.stats.refracted += t.refracted;
        out.stats.hits += t.hits;
    }
    return out;
}

}  // namespace rtlab
