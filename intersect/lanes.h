#pragma once
// Float lanes for intersection methods written once over their scalar: a method's test templated
// on L runs on one primitive with L = float and on lane_count primitives at once with L =
// FloatLanes (GCC vector extensions, so the build's own SIMD: 8 lanes with AVX, 4 without). The
// same operations in the same order give every lane exactly the scalar's result (contraction is
// off in every build). Masks are bool for one primitive and MaskLanes (0 or -1 per lane) for lanes;
// `&` combines both, none() tests both, so a method's early outs stay early outs in float.

#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/vec.h"

#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace rtlab {

#if defined(__AVX__)
inline constexpr unsigned lane_count = 8;
#else
inline constexpr unsigned lane_count = 4;
#endif

/// lane_count floats.
using FloatLanes = float __attribute__((vector_size(4 * lane_count)));
/// lane_count 32-bit integers: a comparison's mask (0 or -1), or per-lane indices.
using MaskLanes = std::int32_t __attribute__((vector_size(4 * lane_count)));

/// True for the lane type, false for a scalar.
template <class L>
inline constexpr bool is_lanes = std::is_same_v<L, FloatLanes>;

/// The mask type of comparisons of L: bool for a scalar, MaskLanes for lanes.
template <class L>
using MaskOf = std::conditional_t<is_lanes<L>, MaskLanes, bool>;

/// x in every lane of L (x itself for a scalar).
template <class L>
inline L splat(float x) {
    if constexpr (is_lanes<L>) {
        return FloatLanes{} + x;
    } else {
        return static_cast<L>(x);
    }
}

/// True when no lane of m is set.
inline bool none(bool m) {
    return !m;
}
inline bool none(MaskLanes m) {
    MaskLanes zero{};
    return std::memcmp(&m, &zero, sizeof m) == 0;
}

/// Every lane set (true for a scalar).
template <class L>
inline MaskOf<L> all_set() {
    if constexpr (is_lanes<L>) {
        return MaskLanes{} == 0;
    } else {
        return true;
    }
}

/// The lanes of m flipped.
inline bool lane_not(bool m) {
    return !m;
}
inline MaskLanes lane_not(MaskLanes m) {
    return ~m;
}

/// The correctly rounded square root, lane by lane.
template <std::floating_point T>
inline T lane_sqrt(T x) {
    return std::sqrt(x);
}
inline FloatLanes lane_sqrt(FloatLanes x) {
#if defined(__AVX__)
    return __builtin_ia32_sqrtps256(x);
#else
    return __builtin_ia32_sqrtps(x);
#endif
}

/// Bit k set when lane k of m is.
inline unsigned lane_bits(MaskLanes m) {
    unsigned bits = 0;
    for (unsigned k = 0; k < lane_count; ++k) {
        bits |= m[k] != 0 ? 1u << k : 0u;
    }
    return bits;
}

/// A 3-vector of lanes: lane k holds one primitive's vector.
struct Vec3Lanes {
    FloatLanes x{}, y{}, z{};
};

/// v in every lane (v itself for a scalar vector).
template <class L, class T>
inline auto splat3(const Vec3<T>& v) {
    if constexpr (is_lanes<L>) {
        return Vec3Lanes{splat<L>(v.x), splat<L>(v.y), splat<L>(v.z)};
    } else {
        return v;
    }
}

/// Lane-wise difference.
inline Vec3Lanes operator-(const Vec3Lanes& a, const Vec3Lanes& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}

/// Lane-wise dot product, in Vec3's order of operations.
inline FloatLanes dot(const Vec3Lanes& a, const Vec3Lanes& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// Lane-wise cross product, in Vec3's order of operations.
inline Vec3Lanes cross(const Vec3Lanes& a, const Vec3Lanes& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Component i of v (an axis index per lane for lanes).
template <class T>
inline T pick(const Vec3<T>& v, std::size_t i) {
    return v[i];
}
inline FloatLanes pick(const Vec3Lanes& v, MaskLanes i) {
    return i == 0 ? v.x : (i == 1 ? v.y : v.z);
}

/// Stores v in lane k of the lane vector out.
template <class T>
inline void set_lane(Vec3Lanes& out, unsigned k, const Vec3<T>& v) {
    out.x[k] = v.x;
    out.y[k] = v.y;
    out.z[k] = v.z;
}

/// What a method's lane test reports: which lanes hit, and their t, u, v.
template <class L>
struct LaneHit {
    MaskOf<L> hit{};
    L t{}, u{}, v{};
};

/// A float method with lanes (see the file comment): `Lanes` holds lane_count prepared primitives
/// and set_lane(lanes, k, prepared) stores one in lane k.
template <class M>
concept HasLanes = std::same_as<typename M::Scalar, float> &&
    requires(typename M::Lanes& g, const typename M::Prepared& p) {
    M::set_lane(g, 0u, p);
};

/// A float method written once over its scalar (see the file comment): test<FloatLanes> tests a
/// ray against all lanes' primitives, each lane exactly as test<float> on its primitive. Its
/// occluded() is the default (a hit of intersect()), and its window only clips the t it reports:
/// a hit with t stays that hit for any window that still holds t, so a leaf kernel may keep a
/// lane's hit after a closer one shrank the window, by comparing t alone.
template <class M>
concept LaneMethod = HasLanes<M> &&(
    requires(const typename M::Lanes& g, const Ray<float>& r) {
        { M::template test<FloatLanes>(g, r) } -> std::same_as<LaneHit<FloatLanes>>;
    } ||
    requires(const typename M::Lanes& g, const Ray<float>& r, const RayDataOf<M>& d) {
        { M::template test<FloatLanes>(g, r, d) } -> std::same_as<LaneHit<FloatLanes>>;
    });

/// An occlusion-only float method written once over its scalar: occludes<FloatLanes> tells which
/// lanes' primitives a ray meets in its window, each lane exactly as occludes<float> (its
/// occluded()) on its primitive.
template <class M>
concept LaneOcclusionMethod = HasLanes<M> &&
    requires(const typename M::Lanes& g, const Ray<float>& r) {
    { M::template occludes<FloatLanes>(g, r) } -> std::same_as<MaskLanes>;
};

/// M's lane test of g for ray r with its per-ray set-up d (precompute_ray<M>).
template <LaneMethod M>
LaneHit<FloatLanes> lane_test(const typename M::Lanes& g,
                              const Ray<float>& r,
                              const RayDataOf<M>& d) {
    if constexpr (HasRayData<M>) {
        return M::template test<FloatLanes>(g, r, d);
    } else {
        return M::template test<FloatLanes>(g, r);
    }
}

/// The lanes of g whose primitive ray r meets in its window, d its set-up (precompute_ray<M>): a
/// LaneMethod's hits, or a LaneOcclusionMethod's answer.
template <HasLanes M>
MaskLanes lane_occluded(const typename M::Lanes& g, const Ray<float>& r, const RayDataOf<M>& d) {
    if constexpr (LaneMethod<M>) {
        return lane_test<M>(g, r, d).hit;
    } else {
        static_assert(LaneOcclusionMethod<M>, "a method with lanes tests them (intersect/lanes.h)");
        return M::template occludes<FloatLanes>(g, r);
    }
}

}  // namespace rtlab
