#pragma once
// The SPD output library's rules (Haines' Standard Procedural Databases, libpr*.c, libtx.c),
// written from their description: a transform stack of 4x4 row-vector matrices (a point is
// transformed as [x y z 1] * M; a new transform applies before the current one), the Phong
// exponent of a highlight half-angle, and primitives appended to an NFF document with the current
// transform applied (radii scaled by the length of the matrix's first row: uniform scaling).

#include "scene/nff_io.h"

#include <array>
#include <vector>

namespace rtlab::gen::spd {

/// 4x4 matrix, row-vector convention (translation in row 3).
struct Mat4 {
    std::array<std::array<double, 4>, 4> m{};
};

/// Identity.
[[nodiscard]] Mat4 identity();
/// Rotation by `angle` radians about coordinate axis 0 (X), 1 (Y) or 2 (Z), right-handed.
[[nodiscard]] Mat4 rotate(int axis, double angle);
/// Rotation by `angle` radians about the unit vector `axis`, right-handed.
[[nodiscard]] Mat4 rotate_about(const Vec3d& axis, double angle);
/// Scale and translation.
[[nodiscard]] Mat4 scale(const Vec3d& s);
[[nodiscard]] Mat4 translate(const Vec3d& t);
/// a then b: [p] * a * b.
[[nodiscard]] Mat4 operator*(const Mat4& a, const Mat4& b);
/// [p 1] * m (affine).
[[nodiscard]] Vec3d transform_point(const Vec3d& p, const Mat4& m);

/// Phong exponent of a highlight that falls to half strength at `ang` degrees off the mirror
/// direction: log(0.5) / log(cos(ang)); 100000 for ang <= 0, 1 for ang >= 90 (lib_output_color).
[[nodiscard]] double phong_power(double ang_deg);

/// Appends records the way the SPD library writes them in NFF.
class Writer {
public:
    void background(const Vec3d& c);
    void view(const Vec3d& from,
              const Vec3d& at,
              const Vec3d& up,
              double angle,
              double hither,
              int width,
              int height);
    /// A light at p (transformed); NFF gets no intensity (see nff::to_scene).
    void light(const Vec3d& p);
    /// lib_output_color(color, ka, kd, ks, ks_spec, ang, kt, ior): NFF keeps kd, ks, the Phong
    /// power of `ang`, kt and ior.
    void color(const Vec3d& c, double kd, double ks, double ang, double kt, double ior);
    void sphere(const Vec3d& center, double radius);
    void cone(const Vec3d& base, double base_radius, const Vec3d& apex, double apex_radius);
    void polygon(const std::vector<Vec3d>& v);
    void patch(const std::vector<Vec3d>& v, const std::vector<Vec3d>& n);

    /// lib_tx_push / lib_tx_pop.
    void push();
    void pop();
    /// The new transform applies before the current one (lib_tx_rotate/scale/translate).
    void apply(const Mat4& m);

    [[nodiscard]] nff::Document take() { return std::move(doc_); }

private:
    [[nodiscard]] double radius_scale() const;
    nff::Document doc_;
    Mat4 tx_ = identity();
    bool active_ = false;
    std::vector<std::pair<Mat4, bool>> stack_;
};

}  // namespace rtlab::gen::spd
