#pragma once
// The data of the parallel binned SAH builder (accel/bvh/build_binned_parallel.cpp, its only
// user): four-float vectors (SSE when available), 32-byte primitive references and boxes of two
// vectors, binned by accel/bvh/binning.h. Plain data with the few operations binning needs.

#include "intersect/bounds.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rtlab::binned {

/// Four floats with the few operations binning needs (SSE when available).
struct V4 {
#if defined(__SSE2__)
    __m128 v;
    static V4 load(const float* p) {
        return {_mm_loadu_ps(p)};
    }
    static V4 splat(float x) {
        return {_mm_set1_ps(x)};
    }
    static V4 set(float x, float y, float z) {
        return {_mm_setr_ps(x, y, z, 0.0f)};
    }
    friend V4 vmin(V4 a, V4 b) {
        return {_mm_min_ps(a.v, b.v)};
    }
    friend V4 vmax(V4 a, V4 b) {
        return {_mm_max_ps(a.v, b.v)};
    }
    friend V4 operator+(V4 a, V4 b) {
        return {_mm_add_ps(a.v, b.v)};
    }
    friend V4 operator-(V4 a, V4 b) {
        return {_mm_sub_ps(a.v, b.v)};
    }
    friend V4 operator*(V4 a, V4 b) {
        return {_mm_mul_ps(a.v, b.v)};
    }
    /// Lanes 0..2 kept, lane 3 zeroed.
    V4 xyz() const {
        return {_mm_and_ps(v, _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)))};
    }
    /// Each lane clamped to [0, top] (a NaN lane becomes 0) and truncated to an integer.
    void bins(float top, int out[4]) const {
        const __m128 f = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(top));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(f));
    }
    void store(float* p) const {
        _mm_storeu_ps(p, v);
    }
    /// x*y + y*z + z*x of lanes 0..2, summed in that order.
    float cross_sum() const {
        const __m128 p = _mm_mul_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 0, 2, 1)));
        const __m128 s = _mm_add_ss(p, _mm_shuffle_ps(p, p, _MM_SHUFFLE(1, 1, 1, 1)));
        return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehl_ps(p, p)));
    }
#else
    float v[4];
    static V4 load(const float* p) {
        return {{p[0], p[1], p[2], p[3]}};
    }
    static V4 splat(float x) {
        return {{x, x, x, x}};
    }
    static V4 set(float x, float y, float z) {
        return {{x, y, z, 0.0f}};
    }
    template <class F>
    static V4 zip(V4 a, V4 b, F f) {
        return {{f(a.v[0], b.v[0]), f(a.v[1], b.v[1]), f(a.v[2], b.v[2]), f(a.v[3], b.v[3])}};
    }
    friend V4 vmin(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x < y ? x : y; });
    }
    friend V4 vmax(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x > y ? x : y; });
    }
    friend V4 operator+(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x + y; });
    }
    friend V4 operator-(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x - y; });
    }
    friend V4 operator*(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x * y; });
    }
    V4 xyz() const {
        return {{v[0], v[1], v[2], 0.0f}};
    }
    void bins(float top, int out[4]) const {
        for (int i = 0; i < 4; ++i) {
            const float f = v[i] > 0.0f ? v[i] : 0.0f;
            out[i] = static_cast<int>(f < top ? f : top);
        }
    }
    void store(float* p) const {
        std::copy(v, v + 4, p);
    }
    float cross_sum() const {
        return v[0] * v[1] + v[1] * v[2] + v[2] * v[0];
    }
#endif
};

/// A primitive reference: its box and id (the id rides in the box minimum's fourth float).
struct alignas(32) PrimRef {
    float lo[3];
    std::uint32_t id;
    float hi[3];
    std::uint32_t pad;

    V4 vlo() const { return V4::load(lo); }
    V4 vhi() const { return V4::load(hi); }
    /// Twice the box centre (lo + hi), lane 3 zero.
    V4 twice_center() const { return (vlo() + vhi()).xyz(); }
};

/// A box as two V4 (lane 3 unused); empty by default.
struct Box {
    V4 lo = V4::splat(std::numeric_limits<float>::infinity());
    V4 hi = V4::splat(-std::numeric_limits<float>::infinity());

    void extend(const Box& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    void extend(V4 p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    void extend(const PrimRef& r) {
        lo = vmin(lo, r.vlo());
        hi = vmax(hi, r.vhi());
    }
    /// Half the surface area of a box known to be non-empty (no stores, no checks).
    float half_area_filled() const { return (hi - lo).cross_sum(); }
    /// Half the surface area; 0 when empty.
    float half_area() const {
        float a[4], b[4];
        lo.store(a);
        hi.store(b);
        const float dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
        if (!(dx >= 0.0f && dy >= 0.0f && dz >= 0.0f)) {
            return 0.0f;
        }
        return dx * dy + dy * dz + dz * dx;
    }
    Bounds3f bounds() const {
        float a[4], b[4];
        lo.store(a);
        hi.store(b);
        return {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}};
    }
};

}  // namespace rtlab::binned
