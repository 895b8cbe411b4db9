#pragma once
// The Whitted renderer (seeds 000, 001, 004): Phong shading with shadow rays, recursive mirror
// reflection and Snell refraction with Fresnel weights, Beer-Lambert absorption, a spectral mode
// for dispersion, solid checker textures, AOVs. Rays travel in batches (one wavefront per tile and
// depth) through SceneTracer; the integrator is compiled once per feature set and the scene's own
// set is picked at run time, so paths a scene does not need are not in the code that runs.

#include "render/image.h"
#include "render/optics.h"
#include "scene/scene.h"
#include "trace/offset.h"
#include "trace/scene_tracer.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab {

/// What the image shows.
enum class Aov {
    color,   ///< radiance (linear)
    depth,   ///< distance from the eye to the first hit (mean over the pixel's samples that
             ///< hit); depth_no_hit where no sample hits
    normal,  ///< first hit's normal facing the eye, mapped to 0.5 * n + 0.5 (0 for misses)
    heatmap  ///< false colour of nodes visited + primitive tests of the eye rays, with a legend
};

/// The depth AOV's value for a pixel none of whose samples hit: negative, never a distance.
inline constexpr float depth_no_hit = -1.0f;

/// Lower-case name of an AOV ("color", "depth", "normal", "heatmap").
std::string_view to_string(Aov a);

/// The AOV called `name`; throws std::invalid_argument for other names.
Aov parse_aov(std::string_view name);

/// Lower-case name of a Fresnel form ("exact", "schlick").
std::string_view fresnel_name(FresnelForm f);

/// The Fresnel form called `name`; throws std::invalid_argument for other names.
FresnelForm parse_fresnel(std::string_view name);

/// How to render. Zero sizes take the scene camera's.
struct RenderSettings {
    int width = 0;      ///< pixels; 0 = camera width
    int height = 0;     ///< pixels; 0 = camera height
    int spp = 1;        ///< samples per pixel (fixed Hammersley points; 1 = pixel centre), >= 1
    int max_depth = 5;  ///< deepest secondary ray (eye rays are depth 0), >= 0
    FresnelForm fresnel = FresnelForm::exact;  ///< used by materials with fresnel = true
    std::optional<bool> spectral;  ///< nullopt: on exactly when the scene has dispersion
    int wavelengths = 8;           ///< spectral samples per eye ray in spectral mode, >= 1
    OffsetPolicy offset = OffsetPolicy::ulp;  ///< how secondary rays leave surfaces
    float epsilon = default_offset_epsilon;   ///< offset for OffsetPolicy::epsilon, >= 0
    Aov aov = Aov::color;
    /// SPD mode: the image from rays through the (W+1) x (H+1) pixel corners, each pixel the mean
    /// of its four corners (spp is ignored).
    bool spd = false;
    bool all_features = false;  ///< run the integrator with every feature compiled in
    int tile = 16;              ///< tile edge in pixels, >= 1
    /// Called after each finished tile with (tiles done, tiles total), from worker threads.
    std::function<void(std::size_t, std::size_t)> progress;
};

/// One line of --explain: a feature, whether it is on, and why.
struct FeatureReason {
    std::string name;
    bool enabled = false;
    std::string why;
};

/// What will run for a scene: its features, the spectral choice and the integrator instance.
struct RenderPlan {
    SceneFeatures features;              ///< from the scene's materials, lights and objects
    bool shadows = false;                ///< compiled into the chosen integrator
    bool reflection = false;             ///< compiled (reflection rays, also for Fresnel/TIR)
    bool refraction = false;             ///< compiled (with Fresnel, absorption, dispersion)
    bool textures = false;               ///< compiled
    bool spectral = false;               ///< one wavelength per traced path
    std::string instantiation;           ///< e.g. "Integrator<shadows, reflection, -, ->"
    std::vector<FeatureReason> reasons;  ///< one per feature, in feature_names order
};

/// The plan for scene s under settings r (throws std::invalid_argument for bad settings).
RenderPlan plan_render(const Scene& s, const RenderSettings& r);

/// Ray and timing figures of one render.
struct RenderStats {
    std::uint64_t eye = 0;        ///< eye rays (spectral mode: one per wavelength)
    std::uint64_t shadow = 0;     ///< shadow rays, including continuations through glass
    std::uint64_t reflected = 0;  ///< reflection rays
    std::uint64_t refracted = 0;  ///< refraction rays
    std::uint64_t hits = 0;       ///< closest-hit rays (eye, reflected, refracted) that hit
    double render_ms = 0;         ///< wall time of rendering (not of building structures)
    double build_ms = 0;          ///< wall time of building the structures
    double heat_min = 0;          ///< heatmap AOV: smallest per-pixel cost (nodes + prims)
    double heat_max = 0;          ///< heatmap AOV: largest per-pixel cost
    /// All rays.
    std::uint64_t total() const { return eye + shadow + reflected + refracted; }
};

/// A rendered image with its plan and statistics.
struct RenderResult {
    Image image;  ///< linear radiance for Aov::color, display values for the other AOVs
    RenderPlan plan;
    RenderStats stats;
};

/// Renders scene s with a prepared tracer (built from s). The image is the same for any thread
/// count. Throws std::invalid_argument for bad settings.
RenderResult render(const Scene& s, const SceneTracer& tracer, const RenderSettings& r);

}  // namespace rtlab
