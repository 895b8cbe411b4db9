// The renderer's optics against analytic answers: Fresnel at normal incidence, energy balance
// R + T = 1 from the transmission amplitudes, total internal reflection past the critical angle,
// Snell's law, Beer-Lambert, Cauchy dispersion and the spectral weights.
#include "render/optics.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace rtlab;

namespace {

/// Transmittance from the Fresnel transmission amplitudes (Born & Wolf 1.5.2), computed without
/// the reflection coefficients, so R + T = 1 is a real check of the reflectance.
double transmittance(double cos_i, double eta_i, double eta_t) {
    const double sin_t = eta_i / eta_t * std::sqrt(1 - cos_i * cos_i);
    const double cos_t = std::sqrt(1 - sin_t * sin_t);
    const double t_par = 2 * eta_i * cos_i / (eta_t * cos_i + eta_i * cos_t);
    const double t_perp = 2 * eta_i * cos_i / (eta_i * cos_i + eta_t * cos_t);
    return eta_t * cos_t / (eta_i * cos_i) * 0.5 * (t_par * t_par + t_perp * t_perp);
}

Vec3d from_angle(double theta) {
    return {std::sin(theta), -std::cos(theta), 0};
}

}  // namespace

TEST_CASE("4 % reflectance at normal incidence from air into glass", "[render][optics]") {
    for (FresnelForm form : {FresnelForm::exact, FresnelForm::schlick}) {
        CHECK(fresnel(form, 1.0, 1.0, 1.5) == Approx(0.04).epsilon(1e-12));
        CHECK(fresnel(form, 1.0, 1.5, 1.0) == Approx(0.04).epsilon(1e-12));
        CHECK(fresnel(form, 1.0f, 1.0f, 1.5f) == Approx(0.04).epsilon(1e-6));
    }
}

TEST_CASE("exact Fresnel reflectance and transmittance sum to 1", "[render][optics]") {
    for (double eta_t : {1.33, 1.5, 2.4}) {
        for (int k = 0; k <= 89; ++k) {
            const double cos_i = std::cos(k * std::numbers::pi / 180);
            const double r = fresnel(FresnelForm::exact, cos_i, 1.0, eta_t);
            CHECK(r + transmittance(cos_i, 1.0, eta_t) == Approx(1.0).epsilon(1e-12));
            CHECK(r >= fresnel(FresnelForm::exact, 1.0, 1.0, eta_t) - 1e-15);  // minimum at 0°
        }
    }
    // Brewster's angle: the parallel coefficient vanishes, R = r_perp^2 / 2.
    const double brewster = std::atan(1.5);
    const double cb = std::cos(brewster), st = std::sin(brewster) / 1.5;
    const double ct = std::sqrt(1 - st * st);
    const double r_perp = (cb - 1.5 * ct) / (cb + 1.5 * ct);
    CHECK(fresnel(FresnelForm::exact, cb, 1.0, 1.5) == Approx(0.5 * r_perp * r_perp));
}

TEST_CASE("total internal reflection past the critical angle", "[render][optics]") {
    const double critical = std::asin(1 / 1.5);
    const Vec3d n{0, 1, 0};
    for (double theta : {critical + 1e-6, critical + 0.1, 1.5}) {
        const Vec3d d = from_angle(theta);
        CHECK_FALSE(refract(d, n, 1.5).has_value());
        for (FresnelForm form : {FresnelForm::exact, FresnelForm::schlick}) {
            CHECK(fresnel(form, std::cos(theta), 1.5, 1.0) == 1.0);
        }
    }
    const Vec3d d = from_angle(critical - 1e-3);
    REQUIRE(refract(d, n, 1.5).has_value());
    CHECK(fresnel(FresnelForm::exact, std::cos(critical - 1e-3), 1.5, 1.0) < 1.0);
}

TEST_CASE("refraction obeys Snell's law and stays in the plane of incidence", "[render][optics]") {
    const Vec3d n{0, 1, 0};
    for (double eta : {1 / 1.5, 1.0, 1 / 1.33}) {
        for (int k = 0; k < 90; k += 7) {
            const double theta = k * std::numbers::pi / 180;
            const auto t = refract(from_angle(theta), n, eta);
            REQUIRE(t.has_value());
            CHECK(length(*t) == Approx(1.0).epsilon(1e-12));
            CHECK(t->y < 0);  // transmitted into the surface
            CHECK(t->z == 0);
            CHECK(t->x == Approx(eta * std::sin(theta)).margin(1e-12));  // sin_t = eta sin_i
        }
    }
    const Vec3d m = reflect(from_angle(0.3), n);
    CHECK(m.x == Approx(std::sin(0.3)));
    CHECK(m.y == Approx(std::cos(0.3)));
}

TEST_CASE("Beer-Lambert attenuation is exp(-alpha s) per channel", "[render][optics]") {
    const Vec3f a{0.5f, 1.0f, 0.0f};
    for (float s : {0.0f, 0.25f, 2.0f, 10.0f}) {
        const Vec3f t = beer_lambert(a, s);
        CHECK(t.x == Approx(std::exp(-0.5 * static_cast<double>(s))));
        CHECK(t.y == Approx(std::exp(-static_cast<double>(s))));
        CHECK(t.z == 1.0f);
        // Two halves of a path attenuate like the whole.
        CHECK(beer_lambert(a, s / 2).x * beer_lambert(a, s / 2).x == Approx(t.x));
    }
}

TEST_CASE("Cauchy dispersion bends blue more than red; spectral weights sum to white",
          "[render][optics]") {
    CHECK(cauchy_ior(1.5f, 0.0f, 450.0f) == 1.5f);
    CHECK(cauchy_ior(1.5f, 0.01f, 400.0f) == Approx(1.5 + 0.01 / 0.16));
    CHECK(cauchy_ior(1.5f, 0.01f, 450.0f) > cauchy_ior(1.5f, 0.01f, 650.0f));
    for (int count : {1, 8, 16, 31}) {
        const auto samples = spectral_samples(count);
        REQUIRE(samples.size() == static_cast<std::size_t>(count));
        Vec3d sum{0, 0, 0};
        for (const SpectralSample& s : samples) {
            CHECK(s.lambda_nm > 380.0f);
            CHECK(s.lambda_nm < 730.0f);
            sum += Vec3d(s.rgb_weight);
        }
        CHECK(sum.x == Approx(1.0).epsilon(1e-5));
        CHECK(sum.y == Approx(1.0).epsilon(1e-5));
        CHECK(sum.z == Approx(1.0).epsilon(1e-5));
    }
    // Red light is mostly red, blue light mostly blue; the luminance peaks near 555 nm.
    const auto s = spectral_samples(35);             // 10 nm strata centred on 385, 395, ...
    CHECK(s[27].rgb_weight.x > s[27].rgb_weight.z);  // 655 nm
    CHECK(s[7].rgb_weight.z > s[7].rgb_weight.x);    // 455 nm
    CHECK(cie_xyz(555).y > cie_xyz(500).y);
    CHECK(cie_xyz(555).y > cie_xyz(610).y);
    CHECK(cie_xyz(555).y == Approx(1.0).epsilon(0.03));
}
