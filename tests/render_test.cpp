// The Whitted renderer against analytic answers (checker x Lambert, Beer-Lambert through a slab),
// and its invariants: the same image from every structure and for any thread count, the feature
// plan of a mirror-only scene, the heat map legend.
#include "accel/any_accel.h"
#include "datasets_gen/generators.h"
#include "render/heatmap.h"
#include "render/renderer.h"
#include "trace/camera.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace rtlab {

namespace {

float max_abs_diff(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    float d = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        d = std::max(d, max_component(abs(a.pixels[i] - b.pixels[i])));
    }
    return d;
}

gen::GenOptions flake_options(int size) {
    gen::GenOptions o;
    o.size = size;
    return o;
}

// A size-1 sphere flake whose spheres are glass (Fresnel, absorption) and mirrors alternately.
Scene glass_and_mirror_flake() {
    Scene s = gen::generate("flake", flake_options(1));
    Material glass;
    glass.name = "glass";
    glass.color = {1, 1, 1};
    glass.diffuse = 0.1f;
    glass.transmit = 0.9f;
    glass.ior = 1.5f;
    glass.fresnel = true;
    glass.absorption = {0.3f, 0.1f, 0.05f};
    s.materials.push_back(glass);
    const auto glass_id = static_cast<std::uint32_t>(s.materials.size() - 1);
    for (std::size_t i = 0; i < s.spheres.size(); i += 2) {
        s.spheres[i].material = glass_id;
    }
    return s;
}

RenderResult render_with(const Scene& s, const std::string& accel, RenderSettings r) {
    TraceSetup setup;
    setup.accel = parse_accel_spec(accel);
    const SceneTracer tracer(s, setup);
    return render(s, tracer, r);
}

/// A 16 x 16 image of box (default material) from (0, 0, 5), looking at the origin.
Scene box_scene(const Bounds3f& box) {
    Scene s;
    s.camera.from = {0, 0, 5};
    s.camera.at = {0, 0, 0};
    s.camera.width = 16;
    s.camera.height = 16;
    s.materials.push_back(Material{});
    s.add(BoxObject{box, 0});
    return s;
}

const FeatureReason& reason(const RenderPlan& p, const std::string& name) {
    const auto it = std::find_if(p.reasons.begin(), p.reasons.end(),
                                 [&](const FeatureReason& f) { return f.name == name; });
    REQUIRE(it != p.reasons.end());
    return *it;
}

}  // namespace

TEST_CASE("every structure renders the same image of mirrors and glass", "[render]") {
    const Scene s = glass_and_mirror_flake();
    RenderSettings r;
    r.width = 24;
    r.height = 24;
    r.max_depth = 4;
    const RenderResult ref = render_with(s, "brute", r);
    CHECK(ref.plan.refraction);
    CHECK(ref.stats.refracted > 0);
    CHECK(ref.stats.reflected > 0);
    CHECK(ref.stats.shadow > 0);
    for (const AccelEntry& e : accel_registry()) {
        CAPTURE(e.name);
        const RenderResult img = render_with(s, std::string(e.name), r);
        CHECK(max_abs_diff(img.image, ref.image) < 1e-4f);
        // Shadow rays too: every blocked one is walked by closest hits, whatever blocker an
        // any-hit query met first.
        CHECK(img.stats.eye == ref.stats.eye);
        CHECK(img.stats.shadow == ref.stats.shadow);
        CHECK(img.stats.reflected == ref.stats.reflected);
        CHECK(img.stats.refracted == ref.stats.refracted);
    }
}

TEST_CASE("the image does not depend on the thread count", "[render]") {
    const Scene s = glass_and_mirror_flake();
    RenderSettings r;
    r.width = 20;
    r.height = 16;
    r.tile = 4;
    r.spp = 2;
    const auto with_threads = [&](std::size_t n) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, n);
        return render_with(s, "bvh:binned", r).image;
    };
    const Image one = with_threads(1);
    const Image two = with_threads(2);
    CHECK(one.pixels == two.pixels);
}

TEST_CASE("a mirror-only scene runs without refraction", "[render]") {
    const Scene s = gen::generate("flake", flake_options(1));
    const RenderPlan p = plan_render(s, RenderSettings{});
    CHECK(p.features.reflection);
    CHECK_FALSE(p.features.refraction);
    CHECK(p.reflection);
    CHECK_FALSE(p.refraction);
    CHECK_FALSE(p.textures);
    CHECK_FALSE(p.spectral);
    CHECK(p.instantiation.find("refraction") == std::string::npos);
    CHECK_FALSE(reason(p, "refraction").enabled);
    CHECK(reason(p, "reflection").enabled);
    CHECK(reason(p, "reflection").why.find("flake") != std::string::npos);
    CHECK_FALSE(reason(p, "mesh").enabled);

    RenderSettings all;
    all.all_features = true;
    const RenderPlan q = plan_render(s, all);
    CHECK(q.refraction);
    CHECK(q.textures);
    CHECK_FALSE(reason(q, "refraction").enabled);  // compiled in, but the scene does not use it

    // Rendering with everything compiled in changes nothing for this scene.
    RenderSettings small;
    small.width = 16;
    small.height = 16;
    all.width = 16;
    all.height = 16;
    CHECK(max_abs_diff(render_with(s, "bvh:binned", small).image,
                       render_with(s, "bvh:binned", all).image) == 0.0f);
}

TEST_CASE("a checker floor pixel is the checker colour times Lambert", "[render]") {
    Scene s;
    s.camera.from = {0.3f, 4, 3};
    s.camera.at = {0.3f, 0, 0};
    s.camera.fov_deg = 50;
    s.camera.width = 32;
    s.camera.height = 32;
    s.lights.push_back({LightKind::directional, {1, 2, 0.5f}, {0.9f, 0.8f, 0.7f}});
    Material floor;
    floor.name = "floor";
    floor.color = {0.9f, 0.2f, 0.1f};
    floor.ambient = 0.1f;
    floor.diffuse = 0.7f;
    floor.texture = {TextureKind::checker, {0.1f, 0.3f, 0.8f}, 0.75f};
    s.materials.push_back(floor);
    s.add(PolygonObject{{{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}, 0, {}});

    RenderSettings r;
    const RenderResult res = render_with(s, "bvh:binned", r);
    CHECK(res.plan.textures);
    const CameraFrame frame(s.camera);
    const Vec3f l = normalize(s.lights[0].position);
    int checked = 0;
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            const Rayf ray =
                frame.ray(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 32, 32);
            if (ray.dir.y >= -0.05f) {
                continue;
            }
            const Vec3f p = ray.at(-ray.org.y / ray.dir.y);
            const float cx = p.x / 0.75f;
            const float cz = p.z / 0.75f;
            const auto near_edge = [](float c) { return std::abs(c - std::round(c)) < 0.01f; };
            if (near_edge(cx) || near_edge(cz)) {
                continue;
            }
            const bool even =
                (static_cast<long long>(std::floor(cx)) + static_cast<long long>(std::floor(cz))) %
                    2 ==
                0;
            const Vec3f c = even ? floor.color : floor.texture.color2;
            const Vec3f expected =
                c * floor.ambient + c * s.lights[0].color * (floor.diffuse * l.y);
            CAPTURE(x, y);
            CHECK(max_component(abs(res.image.at(x, y) - expected)) < 1e-4f);
            ++checked;
        }
    }
    CHECK(checked > 500);
}

TEST_CASE("light through an absorbing slab falls off as exp(-alpha s)", "[render]") {
    Scene s;
    s.camera.from = {0, 0, 5};
    s.camera.at = {0, 0, 0};
    s.camera.fov_deg = 30;
    s.camera.width = 16;
    s.camera.height = 16;
    s.background = {1, 1, 1};
    Material slab;
    slab.name = "slab";
    slab.ambient = 0;
    slab.diffuse = 0;
    slab.transmit = 1;
    slab.ior = 1;  // no bending: every ray crosses the slab on a straight line
    slab.absorption = {0.5f, 1.0f, 2.0f};
    s.materials.push_back(slab);
    s.add(BoxObject{Bounds3f{{-10, -10, -0.5f}, {10, 10, 0.5f}}, 0});

    for (const OffsetPolicy policy : {OffsetPolicy::ulp, OffsetPolicy::epsilon}) {
        RenderSettings r;
        r.offset = policy;
        r.epsilon = 1e-5f;
        const RenderResult res = render_with(s, "bvh:binned", r);
        CHECK(res.plan.refraction);
        CHECK(res.stats.refracted == 2u * 16u * 16u);
        const CameraFrame frame(s.camera);
        for (int y = 0; y < 16; ++y) {
            for (int x = 0; x < 16; ++x) {
                const Rayf ray =
                    frame.ray(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 16, 16);
                const float dist = 1.0f / std::abs(ray.dir.z);  // path length inside the slab
                const Vec3f expected = beer_lambert(slab.absorption, dist);
                CAPTURE(x, y, dist);
                CHECK(max_component(abs(res.image.at(x, y) - expected)) < 2e-4f);
            }
        }
    }
}

TEST_CASE("AOVs: depth is the hit distance, the heat map has its legend", "[render]") {
    const Scene s = box_scene({{-10, -10, -1}, {10, 10, 1}});
    RenderSettings r;
    r.aov = Aov::depth;
    const RenderResult depth = render_with(s, "bvh:binned", r);
    const CameraFrame frame(s.camera);
    const Rayf centre = frame.ray(8.5f, 8.5f, 16, 16);
    CHECK(depth.image.at(8, 8).x == Approx(4.0f / std::abs(centre.dir.z)).epsilon(1e-5));
    CHECK(depth.stats.shadow == 0);

    r.aov = Aov::heatmap;
    const RenderResult heat = render_with(s, "bvh:binned", r);
    CHECK(heat.stats.heat_max >= heat.stats.heat_min);
    CHECK(heat.stats.heat_min > 0);
    // Legend: the ramp (the row under the separator) runs from blue (left) to red (right).
    const int ramp_y = 16 - heatmap_legend(16, 16).rows + 1;
    CHECK(max_component(abs(heat.image.at(0, ramp_y) - Vec3f{0, 0, 1})) < 1e-6f);
    CHECK(max_component(abs(heat.image.at(15, ramp_y) - Vec3f{1, 0, 0})) < 1e-6f);
}

TEST_CASE("depth AOV: a pixel without a hit is depth_no_hit, not depth 0", "[render]") {
    // A small box in the middle: the corners of the image see nothing.
    const Scene s = box_scene({{-0.5f, -0.5f, -1}, {0.5f, 0.5f, 1}});
    RenderSettings r;
    r.aov = Aov::depth;
    r.spp = 4;
    const RenderResult depth = render_with(s, "bvh:binned", r);
    CHECK(depth.image.at(0, 0).x == depth_no_hit);
    CHECK(depth.image.at(15, 15).x == depth_no_hit);
    // Where something is hit, the depth is a distance (the box's front face is 4 away), also on
    // the box's silhouette where only some samples hit (mean over the hits, not over misses).
    int partial = 0;
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 16; ++x) {
            const float d = depth.image.at(x, y).x;
            CAPTURE(x, y, d);
            CHECK((d == depth_no_hit || (d > 3.99f && d < 4.2f)));
            partial += d > 0 ? 1 : 0;
        }
    }
    CHECK(partial > 0);
}

TEST_CASE("heat map legend: tick values and caption in the bar", "[render]") {
    CHECK(heatmap_tick_labels(0, 100) == std::vector<std::string>{"0", "25", "50", "75", "100"});
    CHECK(heatmap_tick_labels(2, 6) == std::vector<std::string>{"2", "3", "4", "5", "6"});
    CHECK(heatmap_tick_labels(1, 3) == std::vector<std::string>{"1.0", "1.5", "2.0", "2.5", "3.0"});
    // A 256 x 256 map from 10 to 90: the legend rows below the ramp carry white text (the tick
    // values and caption); the image above the legend keeps its colours.
    Image img(256, 256);
    for (int y = 0; y < 256; ++y) {
        for (int x = 0; x < 256; ++x) {
            img.at(x, y).x = 10.0f + 80.0f * static_cast<float>(x) / 255.0f;
        }
    }
    colour_heatmap(img, 10, 90);
    const HeatmapLegend l = heatmap_legend(256, 256);
    REQUIRE(l.labels);
    const int text_top = 256 - l.rows + 1 + l.ramp;
    int white = 0;
    for (int y = text_top; y < 256; ++y) {
        for (int x = 0; x < 256; ++x) {
            white += img.at(x, y) == Vec3f{1, 1, 1} ? 1 : 0;
        }
    }
    CHECK(white > 100);
    // The "10" under the left tick (the tick is the row text_top; the digits start 2 font pixels
    // below it): white pixels in the first 8 font columns of the digit rows.
    bool left_number = false;
    const int glyph_top = text_top + 2 * l.scale;
    for (int x = 1; x < 1 + 8 * l.scale; ++x) {
        for (int y = glyph_top; y < glyph_top + 5 * l.scale; ++y) {
            left_number = left_number || img.at(x, y) == Vec3f{1, 1, 1};
        }
    }
    CHECK(left_number);
    CHECK(max_component(abs(img.at(0, 0) - false_colour(0))) < 1e-6f);
    CHECK(max_component(abs(img.at(255, 0) - false_colour(1))) < 1e-6f);
}

TEST_CASE("per-ray counts add up to the batch counts and keep the hits", "[render][trace]") {
    const Scene s = glass_and_mirror_flake();
    const SceneTracer tracer(s, TraceSetup{});
    const CameraFrame frame(s.camera);
    std::vector<Rayf> rays;
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 12; ++x) {
            rays.push_back(
                frame.ray(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 12, 12));
        }
    }
    std::vector<Hit> plain(rays.size());
    std::vector<Hit> counted(rays.size());
    std::vector<TraversalStats> per_ray(rays.size());
    TraversalStats total;
    tracer.intersect(rays, plain, &total);
    tracer.intersect_counted(rays, counted, per_ray);
    TraversalStats sum;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CHECK(counted[i].prim == plain[i].prim);
        CHECK(counted[i].t == plain[i].t);
        sum += per_ray[i];
    }
    CHECK(sum.nodes == total.nodes);
    CHECK(sum.prims == total.prims);
    CHECK(sum.rays == total.rays);
}

TEST_CASE("SPD mode traces the pixel corners and averages them", "[render]") {
    const Scene s = gen::generate("flake", flake_options(0));
    RenderSettings spd;
    spd.spd = true;
    spd.width = 6;
    spd.height = 5;
    const RenderResult res = render_with(s, "bvh:binned", spd);
    CHECK(res.image.width == 6);
    CHECK(res.image.height == 5);
    CHECK(res.stats.eye == 7u * 6u);
    RenderSettings plain;
    plain.width = 6;
    plain.height = 5;
    const RenderResult centres = render_with(s, "bvh:binned", plain);
    CHECK(centres.stats.eye == 6u * 5u);
    // Other sample positions of the same scene: close on average, not identical.
    float sum = 0;
    for (std::size_t i = 0; i < res.image.pixels.size(); ++i) {
        sum += max_component(abs(res.image.pixels[i] - centres.image.pixels[i]));
    }
    CHECK(sum > 0);
    CHECK(sum / static_cast<float>(res.image.pixels.size()) < 0.5f);
}

}  // namespace rtlab
