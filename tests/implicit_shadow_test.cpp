// scenes/implicit.json once rendered a dozen isolated dark pixels on the torus: shadow rays to the
// point light, leaving the crest of the tube (normal ~ +z), were blocked by the torus itself. The
// clipped window there is tiny (the ray leaves the torus's box after ~2e-4), so the ray quartic's
// leading coefficients are ~1e-11 of the others; Ferrari divided by them and reported a root the
// polynomial does not have. solve_closed_form_unit drops such coefficients first.
#include "intersect/implicit/closed_form.h"
#include "intersect/vec.h"
#include "scene/scene.h"
#include "scene/scene_io.h"
#include "trace/camera.h"
#include "trace/offset.h"
#include "trace/scene_tracer.h"
#include "trace/surface.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

using namespace rtlab;

TEST_CASE("closed form on the unit window: negligible leading terms give no phantom root",
          "[intersect][implicit][roots]") {
    // The quartic of the shadow ray from pixel (187, 121) of scenes/implicit.json, in float:
    // positive on all of [0, 1] (every coefficient is), so no root there.
    const Polynomial<float, 4> p{
        {1.23978e-5f, 2.39783e-4f, 1.36082e-7f, 3.91868e-11f, 5.06421e-15f}};
    float u = 0;
    CHECK_FALSE(solve_closed_form_unit(p).first_in(0.0f, 1.0f, u));
    // A well-scaled quartic keeps every root: (u - 0.2)(u - 0.5)(u - 0.7)(u - 0.9).
    const Polynomial<double, 4> q{{0.063, -0.601, 1.85, -2.3, 1.0}};
    const RealRoots<double, 4> r = solve_closed_form_unit(q);
    REQUIRE(r.count == 4);
    CHECK(r.t[0] == Approx(0.2));
    CHECK(r.t[3] == Approx(0.9));
    // A genuine root near 0 of a nearly linear polynomial survives the degree drop.
    const Polynomial<float, 4> lin{{-1e-5f, 2.4e-4f, 1.4e-7f, 3.9e-11f, 5e-15f}};
    REQUIRE(solve_closed_form_unit(lin).first_in(0.0f, 1.0f, u));
    CHECK(u == Approx(1e-5 / 2.4e-4).epsilon(1e-3));
}

TEST_CASE("implicit scene: no self-shadowed pixels on the torus crest", "[render][implicit]") {
    const std::filesystem::path scene_file =
        std::filesystem::path(RTLAB_TEST_DATA_DIR).parent_path().parent_path() / "scenes" /
        "implicit.json";
    const Scene s = load_scene(scene_file);
    const SceneTracer tracer(s, TraceSetup{});  // default methods: closed form for implicits
    const std::vector<std::uint32_t> base = primitive_id_base(s);
    const CameraFrame frame(s.camera);
    REQUIRE(!s.lights.empty());
    const Vec3f light = s.lights[0].position;
    // The pixels (x, y) that were dark in `rtlab render scenes/implicit.json` (default offset).
    const int pixels[][2] = {{187, 121}, {207, 122}, {212, 123}, {173, 124},
                             {211, 124}, {169, 127}, {142, 145}, {266, 200},
                             {267, 202}, {266, 203}, {267, 205}, {263, 218}};
    for (const auto& px : pixels) {
        const Rayf eye =
            frame.ray(static_cast<float>(px[0]) + 0.5f, static_cast<float>(px[1]) + 0.5f,
                      s.camera.width, s.camera.height);
        Hit hit;
        tracer.intersect(std::span<const Rayf>(&eye, 1), std::span<Hit>(&hit, 1));
        CAPTURE(px[0], px[1]);
        REQUIRE(hit.valid());
        CHECK(hit.prim == base[1]);  // the torus (object 1)
        const SurfacePoint sp = surface_at(s, base, hit, eye);
        for (const OffsetPolicy policy : {OffsetPolicy::ulp, OffsetPolicy::epsilon}) {
            const Vec3f org = offset_origin(sp.p, sp.n, policy, 1e-4f);
            const Vec3f to = light - org;
            const Rayf shadow{org, normalize(to), 0.0f, length(to)};
            REQUIRE(dot(sp.n, shadow.dir) > 0);  // lit side: the integrator sends this ray
            std::uint32_t blocker = 0;
            tracer.occluded(std::span<const Rayf>(&shadow, 1),
                            std::span<std::uint32_t>(&blocker, 1));
            CAPTURE(static_cast<int>(policy), blocker);
            CHECK(blocker == invalid_id);
        }
    }
}
