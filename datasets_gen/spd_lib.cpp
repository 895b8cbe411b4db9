// The SPD output library's transform and record rules (see spd_lib.h).
#include "datasets_gen/spd_lib.h"

#include <cmath>
#include <numbers>

namespace rtlab::gen::spd {

Mat4 identity() {
    Mat4 r;
    for (std::size_t i = 0; i < 4; ++i) {
        r.m[i][i] = 1;
    }
    return r;
}

Mat4 rotate(int axis, double angle) {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    Mat4 r = identity();
    const auto a = static_cast<std::size_t>((axis + 1) % 3);  // the plane (a, b) turns
    const auto b = static_cast<std::size_t>((axis + 2) % 3);
    r.m[a][a] = c;
    r.m[b][b] = c;
    r.m[a][b] = s;
    r.m[b][a] = -s;
    return r;
}

Mat4 rotate_about(const Vec3d& axis, double angle) {
    // Rodrigues' rotation matrix, transposed for row vectors.
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const double t = 1 - c;
    const double x = axis.x;
    const double y = axis.y;
    const double z = axis.z;
    Mat4 r = identity();
    r.m[0] = {x * x + (1 - x * x) * c, x * y * t + z * s, x * z * t - y * s, 0};
    r.m[1] = {x * y * t - z * s, y * y + (1 - y * y) * c, y * z * t + x * s, 0};
    r.m[2] = {x * z * t + y * s, y * z * t - x * s, z * z + (1 - z * z) * c, 0};
    return r;
}

Mat4 scale(const Vec3d& s) {
    Mat4 r = identity();
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

Mat4 translate(const Vec3d& t) {
    Mat4 r = identity();
    r.m[3] = {t.x, t.y, t.z, 1};
    return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (std::size_t i = 0; i < 4; ++i) {
        for (std::size_t j = 0; j < 4; ++j) {
            double sum = 0;
            for (std::size_t k = 0; k < 4; ++k) {
                sum += a.m[i][k] * b.m[k][j];
            }
            r.m[i][j] = sum;
        }
    }
    return r;
}

Vec3d transform_point(const Vec3d& p, const Mat4& m) {
    const double v[4] = {p.x, p.y, p.z, 1};
    double out[3] = {0, 0, 0};
    for (std::size_t j = 0; j < 3; ++j) {
        for (std::size_t i = 0; i < 4; ++i) {
            out[j] += v[i] * m.m[i][j];
        }
    }
    return {out[0], out[1], out[2]};
}

double phong_power(double ang_deg) {
    const double a = std::numbers::pi * ang_deg / 180.0;
    if (a <= 0) {
        return 100000.0;
    }
    if (a >= std::numbers::pi / 2) {
        return 1.0;
    }
    return std::log(0.5) / std::log(std::cos(a));
}

void Writer::background(const Vec3d& c) {
    doc_.records.push_back(nff::Background{c});
}

void Writer::view(const Vec3d& from,
                  const Vec3d& at,
                  const Vec3d& up,
                  double angle,
                  double hither,
                  int width,
                  int height) {
    doc_.records.push_back(nff::View{from, at, up, angle, hither, width, height});
}

void Writer::light(const Vec3d& p) {
    nff::Light l;
    l.position = active_ ? transform_point(p, tx_) : p;
    doc_.records.push_back(l);
}

void Writer::color(const Vec3d& c, double kd, double ks, double ang, double kt, double ior) {
    doc_.records.push_back(nff::Fill{c, kd, ks, phong_power(ang), kt, ior});
}

double Writer::radius_scale() const {
    const auto& r = tx_.m[0];
    return std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

void Writer::sphere(const Vec3d& center, double radius) {
    if (active_) {
        doc_.records.push_back(nff::Sphere{transform_point(center, tx_), radius * radius_scale()});
    } else {
        doc_.records.push_back(nff::Sphere{center, radius});
    }
}

void Writer::cone(const Vec3d& base, double base_radius, const Vec3d& apex, double apex_radius) {
    if (active_) {
        const double k = radius_scale();
        doc_.records.push_back(nff::Cone{transform_point(base, tx_), base_radius * k,
                                         transform_point(apex, tx_), apex_radius * k});
    } else {
        doc_.records.push_back(nff::Cone{base, base_radius, apex, apex_radius});
    }
}

void Writer::polygon(const std::vector<Vec3d>& v) {
    nff::Polygon p;
    for (const Vec3d& q : v) {
        p.vertices.push_back(active_ ? transform_point(q, tx_) : q);
    }
    doc_.records.push_back(std::move(p));
}

void Writer::patch(const std::vector<Vec3d>& v, const std::vector<Vec3d>& n) {
    doc_.records.push_back(nff::Polygon{v, n});
}

void Writer::push() {
    stack_.emplace_back(tx_, active_);
}

void Writer::pop() {
    if (!stack_.empty()) {
        tx_ = stack_.back().first;
        active_ = stack_.back().second;
        stack_.pop_back();
    }
}

void Writer::apply(const Mat4& m) {
    tx_ = m * tx_;
    active_ = true;
}

}  // namespace rtlab::gen::spd
