#pragma once
// Vec3: a small 3-vector templated on the scalar, so every kernel can run in float and double.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace rtlab {

/// A 3-vector of floating-point scalars; components are public and contiguous.
template <class T>
struct Vec3 {
    static_assert(std::is_floating_point_v<T>, "Vec3 holds float, double or long double");
    using Scalar = T;

    T x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    /// Explicit conversion between precisions (float <-> double).
    template <class U>
    constexpr explicit Vec3(const Vec3<U>& v)
        : x(static_cast<T>(v.x)), y(static_cast<T>(v.y)), z(static_cast<T>(v.z)) {}

    /// Component by axis index 0, 1, 2.
    constexpr T& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr T operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(const Vec3& b) { return *this = *this + b; }
    constexpr Vec3& operator-=(const Vec3& b) { return *this = *this - b; }
    constexpr Vec3& operator*=(T s) { return *this = *this * s; }

    friend constexpr Vec3 operator+(const Vec3& a, const Vec3& b) {
        return {a.x + b.x, a.y + b.y, a.z + b.z};
    }
    friend constexpr Vec3 operator-(const Vec3& a, const Vec3& b) {
        return {a.x - b.x, a.y - b.y, a.z - b.z};
    }
    /// Component-wise product.
    friend constexpr Vec3 operator*(const Vec3& a, const Vec3& b) {
        return {a.x * b.x, a.y * b.y, a.z * b.z};
    }
    friend constexpr Vec3 operator*(const Vec3& a, T s) { return {a.x * s, a.y * s, a.z * s}; }
    friend constexpr Vec3 operator*(T s, const Vec3& a) { return {a.x * s, a.y * s, a.z * s}; }
    friend constexpr Vec3 operator/(const Vec3& a, T s) { return {a.x / s, a.y / s, a.z / s}; }
    friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

/// Dot product.
template <class T>
constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// Cross product (right-handed).
template <class T>
constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Squared Euclidean length.
template <class T>
constexpr T length_squared(const Vec3<T>& a) {
    return dot(a, a);
}

/// Euclidean length.
template <class T>
T length(const Vec3<T>& a) {
    return std::sqrt(dot(a, a));
}

/// Unit vector in the direction of a (a must be non-zero).
template <class T>
Vec3<T> normalize(const Vec3<T>& a) {
    return a / length(a);
}

/// Component-wise minimum.
template <class T>
constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}

/// Component-wise maximum.
template <class T>
constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

/// Component-wise absolute value.
template <class T>
Vec3<T> abs(const Vec3<T>& a) {
    return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}

/// Index (0, 1, 2) of the component with the largest absolute value; ties pick the lowest index.
template <class T>
std::size_t max_abs_axis(const Vec3<T>& a) {
    const Vec3<T> m = abs(a);
    if (m.x >= m.y && m.x >= m.z) {
        return 0;
    }
    return m.y >= m.z ? 1 : 2;
}

/// Largest component.
template <class T>
constexpr T max_component(const Vec3<T>& a) {
    return std::max(a.x, std::max(a.y, a.z));
}

/// Smallest component.
template <class T>
constexpr T min_component(const Vec3<T>& a) {
    return std::min(a.x, std::min(a.y, a.z));
}

/// True when every component is finite (no NaN, no infinity).
template <class T>
bool is_finite(const Vec3<T>& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace rtlab
