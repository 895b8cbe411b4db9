#pragma once
// Optics of the Whitted renderer: mirror reflection, Snell refraction with total internal
// reflection, the Fresnel reflectance (exact unpolarised and Schlick's approximation),
// Beer-Lambert absorption, Cauchy dispersion and the spectral samples that turn wavelengths into
// linear sRGB. Pure functions of their arguments; no epsilons (callers offset the new rays).

#include "intersect/vec.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace rtlab {

/// Mirror direction of d about the unit normal n (either orientation).
template <class T>
Vec3<T> reflect(const Vec3<T>& d, const Vec3<T>& n) {
    return d - n * (T(2) * dot(d, n));
}

/// Snell's law: the refracted direction of the unit direction d at a surface with unit normal n
/// facing against d (dot(d, n) <= 0), where eta = n_incident / n_transmitted. The result is a unit
/// vector; nullopt means total internal reflection.
template <class T>
std::optional<Vec3<T>> refract(const Vec3<T>& d, const Vec3<T>& n, T eta) {
    const T cos_i = std::min(T(1), -dot(d, n));
    const T sin2_t = eta * eta * std::max(T(0), T(1) - cos_i * cos_i);
    if (sin2_t >= T(1)) {
        return std::nullopt;
    }
    const T cos_t = std::sqrt(T(1) - sin2_t);
    return d * eta + n * (eta * cos_i - cos_t);
}

/// Which Fresnel reflectance to use.
enum class FresnelForm { exact, schlick };

/// Fraction of light reflected at a dielectric boundary, unpolarised, for the cosine cos_i in
/// [0, 1] of the angle of incidence, going from index eta_i into index eta_t. 1 under total
/// internal reflection. The transmitted fraction is 1 - R.
///   exact:   the average of the squared parallel and perpendicular Fresnel amplitude
///            coefficients (Born & Wolf, "Principles of Optics", 1.5.2);
///   schlick: Schlick 1994, "An inexpensive BRDF model for physically-based rendering":
///            R0 + (1 - R0)(1 - c)^5 with c the cosine on the optically thinner side, so that
///            the curve also holds when leaving the denser medium.
template <class T>
T fresnel(FresnelForm form, T cos_i, T eta_i, T eta_t) {
    cos_i = std::clamp(cos_i, T(0), T(1));
    const T ratio = eta_i / eta_t;
    const T sin2_t = ratio * ratio * (T(1) - cos_i * cos_i);
    if (sin2_t >= T(1)) {
        return T(1);
    }
    const T cos_t = std::sqrt(T(1) - sin2_t);
    if (form == FresnelForm::schlick) {
        const T r = (eta_i - eta_t) / (eta_i + eta_t);
        const T r0 = r * r;
        const T c = T(1) - (eta_i > eta_t ? cos_t : cos_i);
        return r0 + (T(1) - r0) * c * c * c * c * c;
    }
    const T r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    const T r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    return T(0.5) * (r_par * r_par + r_perp * r_perp);
}

/// Beer-Lambert law: the fraction of light left per channel after `distance` through a medium
/// with absorption coefficient `absorption` (per unit length): exp(-absorption * distance).
inline Vec3f beer_lambert(const Vec3f& absorption, float distance) {
    return {std::exp(-absorption.x * distance), std::exp(-absorption.y * distance),
            std::exp(-absorption.z * distance)};
}

/// Cauchy's dispersion formula n(lambda) = a + b / lambda^2 with lambda in micrometres, as
/// Material::dispersion documents (b in um^2); lambda_nm is the wavelength in nanometres.
inline float cauchy_ior(float a, float b_um2, float lambda_nm) {
    const float um = lambda_nm * 1e-3f;
    return a + b_um2 / (um * um);
}

/// One wavelength of a spectral render and the linear sRGB it contributes per unit radiance.
struct SpectralSample {
    float lambda_nm = 550;
    Vec3f rgb_weight;
};

/// CIE 1931 2-degree colour matching functions (x, y, z) at lambda_nm, by the multi-lobe
/// Gaussian fit of Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ
/// Color Matching Functions" (JCGT 2(2)).
inline Vec3d cie_xyz(double lambda_nm) {
    const auto g = [lambda_nm](double mu, double s1, double s2) {
        const double t = (lambda_nm - mu) / (lambda_nm < mu ? s1 : s2);
        return std::exp(-0.5 * t * t);
    };
    return {
        1.056 * g(599.8, 37.9, 31.0) + 0.362 * g(442.0, 16.0, 26.7) - 0.065 * g(501.1, 20.4, 26.2),
        0.821 * g(568.8, 46.9, 40.5) + 0.286 * g(530.9, 16.3, 31.1),
        1.217 * g(437.0, 11.8, 36.0) + 0.681 * g(459.0, 26.0, 13.8)};
}

/// `count` (>= 1) stratified wavelengths over 380..730 nm with their linear sRGB weights: CIE XYZ
/// converted by the sRGB (D65) matrix of IEC 61966-2-1, then scaled per channel so the weights
/// sum to (1, 1, 1): a flat spectrum stays white. Single wavelengths may have negative
/// components (outside the sRGB gamut); the image clamps at the end.
inline std::vector<SpectralSample> spectral_samples(int count) {
    count = std::max(count, 1);
    constexpr double lo = 380, hi = 730;
    std::vector<Vec3d> rgb(static_cast<std::size_t>(count));
    std::vector<SpectralSample> out(rgb.size());
    Vec3d sum{0, 0, 0};
    for (std::size_t k = 0; k < rgb.size(); ++k) {
        const double lambda =
            lo + (static_cast<double>(k) + 0.5) * (hi - lo) / static_cast<double>(count);
        const Vec3d c = cie_xyz(lambda);
        rgb[k] = {3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
                  -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
                  0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z};
        sum += rgb[k];
        out[k].lambda_nm = static_cast<float>(lambda);
    }
    for (std::size_t k = 0; k < rgb.size(); ++k) {
        out[k].rgb_weight = Vec3f(Vec3d{rgb[k].x / sum.x, rgb[k].y / sum.y, rgb[k].z / sum.z});
    }
    return out;
}

}  // namespace rtlab
