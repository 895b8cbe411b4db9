// AABB slabs (fast and robust) and OBB slabs: zero, -0.0 and denormal direction components,
// origins on faces and edges, no NaN in hits, fast vs robust, robust on grazing rays, OBB vs AABB.
#include "intersect/box/methods.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

using namespace rtlab;

namespace {

/// Calls f.template operator()<M>() for both AABB methods in both precisions.
template <class F>
void for_all_aabb(F&& f) {
    for_each_aabb_method<float>(f);
    for_each_aabb_method<double>(f);
}

template <class T>
Bounds3<T> unit_box() {
    return {{T(0), T(0), T(0)}, {T(1), T(1), T(1)}};
}

/// The OBB equal to the AABB b (identity axes).
template <class T>
Obb<T> obb_of(const Bounds3<T>& b) {
    return {b.center(),
            {{T(1), T(0), T(0)}, {T(0), T(1), T(0)}, {T(0), T(0), T(1)}},
            b.diagonal() * T(0.5)};
}

/// Checks a hit's t is finite, not NaN, and inside the window.
template <class T>
void check_sane(const std::optional<PrimHit<T>>& h, const Ray<T>& r) {
    if (h) {
        CHECK_FALSE(std::isnan(h->t));
        CHECK(h->t >= r.tmin);
        CHECK(h->t <= r.tmax);
    }
}

/// clip_slabs_ahead (robust traversal's test for windows from tmin >= 0) on b for r's window.
bool ahead_hits(const Bounds3f& b, const Rayf& r) {
    const SlabRay<float> sr(r);
    float t0 = r.tmin, t1 = r.tmax;
    return clip_slabs_ahead(b.lo, b.hi, sr, PaddedInv<float>(sr), t0, t1);
}

}  // namespace

TEST_CASE("slabs: entry t, inside origin, window", "[intersect][box]") {
    for_all_aabb([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        const auto b = M::prepare(unit_box<T>());
        const Ray<T> r{{T(-1), T(0.5), T(0.5)}, {T(2), T(0), T(0)}};
        const auto h = M::intersect(b, r);
        REQUIRE(h);
        CHECK(h->t == Approx(0.5).epsilon(1e-6));
        CHECK(h->u == T(0));
        // Origin inside: t = tmin.
        Ray<T> in{{T(0.5), T(0.5), T(0.5)}, {T(1), T(2), T(3)}, T(0.125)};
        REQUIRE(M::intersect(b, in));
        CHECK(M::intersect(b, in)->t == T(0.125));
        // Window ends before the box / starts after it.
        Ray<T> w = r;
        w.tmax = T(0.49);
        CHECK_FALSE(M::intersect(b, w));
        w.tmin = T(1.01);
        w.tmax = T(5);
        CHECK_FALSE(M::occluded(b, w));
        // Pointing away.
        CHECK_FALSE(M::intersect(b, Ray<T>{{T(-1), T(0.5), T(0.5)}, {T(-1), T(0), T(0)}}));
        CHECK(M::bounds(b) == unit_box<T>());
    });
}

TEST_CASE("slabs: zero direction components on one and two axes", "[intersect][box]") {
    for_all_aabb([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        const auto b = M::prepare(unit_box<T>());
        for (const T zero : {T(0), T(-0.0)}) {
            CAPTURE(std::signbit(zero));
            // One zero component: origin inside, outside and exactly on each face plane.
            for (const T y : {T(0.5), T(1.5), T(-0.5), T(0), T(1)}) {
                const Ray<T> r{{T(-1), y, T(0.5)}, {T(1), zero, T(0.25)}};
                const auto h = M::intersect(b, r);
                check_sane(h, r);
                CHECK(h.has_value() == (y >= T(0) && y <= T(1)));
                if (h) {
                    CHECK(h->t == Approx(1).epsilon(1e-6));
                }
            }
            // Two zero components: along x; (y, z) inside, outside, on a face, on an edge.
            const T yz[][2] = {{T(0.5), T(0.5)}, {T(0), T(0.5)},     {T(1), T(1)},   {T(0), T(0)},
                               {T(1.5), T(0.5)}, {T(0.5), T(-0.01)}, {T(1), T(1.01)}};
            for (const auto& q : yz) {
                CAPTURE(q[0], q[1]);
                for (const T dx : {T(1), T(-1)}) {
                    const Ray<T> r{{dx > 0 ? T(-2) : T(3), q[0], q[1]}, {dx, zero, zero}};
                    const auto h = M::intersect(b, r);
                    check_sane(h, r);
                    const bool in = q[0] >= 0 && q[0] <= 1 && q[1] >= 0 && q[1] <= 1;
                    CHECK(h.has_value() == in);
                    if (h) {
                        CHECK(h->t == Approx(2).epsilon(1e-6));
                    }
                }
            }
            // Origin on an edge (x = 0, y = 0) moving along z from inside the face planes.
            const Ray<T> edge{{T(0), T(0), T(-1)}, {zero, zero, T(1)}};
            const auto he = M::intersect(b, edge);
            REQUIRE(he);
            CHECK(he->t == Approx(1).epsilon(1e-6));
            // Origin on a corner, pointing out along the face diagonal, zero z.
            const Ray<T> corner{{T(1), T(1), T(1)}, {T(1), T(1), zero}};
            const auto hc = M::intersect(b, corner);
            REQUIRE(hc);  // touches at t = 0
            CHECK(hc->t == T(0));
        }
    });
}

TEST_CASE("slabs: denormal direction components never produce NaN", "[intersect][box]") {
    for_all_aabb([]<class M>() {
        using T = typename M::Scalar;
        CAPTURE(M::name, sizeof(T));
        const auto b = M::prepare(unit_box<T>());
        const T den = std::numeric_limits<T>::denorm_min();
        for (const T d : {den, -den, T(16) * den}) {
            for (const T y : {T(0.5), T(0), T(1), T(2)}) {
                const Ray<T> r{{T(-1), y, T(0.5)}, {T(1), d, T(0)}};
                const auto h = M::intersect(b, r);
                check_sane(h, r);
                // The exact ray stays within 1e-30 of y over the box: a hit iff y is inside.
                if (y != T(0) && y != T(1)) {
                    CHECK(h.has_value() == (y >= T(0) && y <= T(1)));
                }
            }
        }
    });
}

TEST_CASE("slabs: fast and robust agree away from the boundary", "[intersect][box]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-3.0f, 3.0f);
    const Bounds3f box{{-0.5f, -0.25f, 0.0f}, {1.0f, 0.75f, 0.5f}};
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const Rayf r{{uni(rng), uni(rng), uni(rng)}, {uni(rng), uni(rng), uni(rng)}};
        const auto hf = AabbSlabs<float>::intersect(box, r);
        const auto hr = AabbSlabsRobust<float>::intersect(box, r);
        // Decide "away from the boundary" in double: the distance of the double ray to the box
        // boundary is larger than 1e-4 at the entry (robust pads by a relative ~7e-7 only).
        const auto hd = AabbSlabs<double>::intersect(Bounds3d{Vec3d(box.lo), Vec3d(box.hi)},
                                                     static_cast<Rayd>(r));
        Bounds3d grown{Vec3d(box.lo) - Vec3d{1e-4, 1e-4, 1e-4},
                       Vec3d(box.hi) + Vec3d{1e-4, 1e-4, 1e-4}};
        Bounds3d shrunk{Vec3d(box.lo) + Vec3d{1e-4, 1e-4, 1e-4},
                        Vec3d(box.hi) - Vec3d{1e-4, 1e-4, 1e-4}};
        const bool in_grown = AabbSlabs<double>::intersect(grown, static_cast<Rayd>(r)).has_value();
        const bool in_shrunk =
            AabbSlabs<double>::intersect(shrunk, static_cast<Rayd>(r)).has_value();
        if (in_grown == in_shrunk) {
            CHECK(hf.has_value() == hr.has_value());
            CHECK(hf.has_value() == hd.has_value());
            hits += hf ? 1 : 0;
        }
        if (hf) {
            REQUIRE(hr);  // robust is never stricter than fast
            CHECK(hr->t <= hf->t);
        }
    }
    CHECK(hits > 200);
}

TEST_CASE("slabs_robust never misses a box the exact ray grazes", "[intersect][box]") {
    // Rays that run inside a face plane (origin on the plane, zero normal component) or leave a
    // box exactly at an edge, for boxes whose faces are not simple powers of two; the exact ray
    // touches the closed box in every case, so the robust method must report a hit, and so must
    // clip_slabs_ahead for the windows from tmin = 0.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(-2.0f, 2.0f);
    int tested = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3f lo{uni(rng), uni(rng), uni(rng)};
        const Vec3f hi = lo + Vec3f{std::abs(uni(rng)) + 0.01f, std::abs(uni(rng)) + 0.01f,
                                    std::abs(uni(rng)) + 0.01f};
        const Bounds3f box{lo, hi};
        // Exit point on an edge: the corner-adjacent edge at x = hi.x, y = hi.y, z inside.
        const Vec3f target{hi.x, hi.y, lo.z + 0.5f * (hi.z - lo.z)};
        const Vec3f org{uni(rng), uni(rng), uni(rng)};
        if (box.contains(org)) {
            continue;
        }
        // Ray through org and target: dir = target - org is rounded, so the exact ray passes
        // near but not exactly through the edge; use the double ray to decide the truth.
        const Rayf r{org, target - org};
        const bool exact =
            AabbSlabs<double>::intersect(Bounds3d{Vec3d(lo), Vec3d(hi)}, static_cast<Rayd>(r))
                .has_value();
        // Double rounding is ~1e-16 relative, float padding ~7e-7: the double answer is exact
        // except within 1e-15 of the boundary, which float inputs at this scale never reach.
        if (exact) {
            ++tested;
            CHECK(AabbSlabsRobust<float>::intersect(box, r));
            CHECK(ahead_hits(box, r));
        }
        // In a face plane: origin with y = lo.y exactly, zero y direction.
        const Rayf in_plane{{org.x, lo.y, org.z}, {target.x - org.x, 0.0f, target.z - org.z}};
        const bool exact2 = AabbSlabs<double>::intersect(Bounds3d{Vec3d(lo), Vec3d(hi)},
                                                         static_cast<Rayd>(in_plane))
                                .has_value();
        if (exact2) {
            CHECK(AabbSlabsRobust<float>::intersect(box, in_plane));
            CHECK(ahead_hits(box, in_plane));
        }
        // A window with tmin < 0 and the box behind the origin (the sign-aware padding).
        const Rayf back{target + (target - org), target - org, -2.0f, 0.0f};
        const bool exact3 =
            AabbSlabs<double>::intersect(Bounds3d{Vec3d(lo), Vec3d(hi)}, static_cast<Rayd>(back))
                .has_value();
        if (exact3) {
            CHECK(AabbSlabsRobust<float>::intersect(box, back));
        }
    }
    CHECK(tested > 100);
}

TEST_CASE("obb_slabs equals slabs for identity axes", "[intersect][box][obb]") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(-2.0, 2.0);
    const Bounds3d box{{-0.5, -0.25, 0.0}, {1.0, 0.75, 0.5}};  // centre and half exact
    const auto ob = ObbSlabs<double>::prepare(obb_of(box));
    CHECK(ObbSlabs<double>::bounds(ob).contains(box));
    for (int i = 0; i < 5000; ++i) {
        Rayd r{{uni(rng), uni(rng), uni(rng)}, {uni(rng), uni(rng), uni(rng)}};
        if (i % 4 == 1) {
            r.dir.y = 0;  // parallel to the y slab
        } else if (i % 4 == 2) {
            r.dir.x = r.dir.z = -0.0;
        }
        const auto ha = AabbSlabs<double>::intersect(box, r);
        const auto ho = ObbSlabs<double>::intersect(ob, r);
        REQUIRE(ha.has_value() == ho.has_value());
        if (ha) {
            CHECK(ho->t == Approx(ha->t).epsilon(1e-12).margin(1e-12));
        }
    }
}

TEST_CASE("obb_slabs: rotated box and rays parallel to a slab", "[intersect][box][obb]") {
    // Box rotated 45 degrees about z: x' = (x + y)/sqrt2, y' = (-x + y)/sqrt2, z' = z.
    const double s = std::sqrt(0.5);
    const Obb<double> b{{0, 0, 0}, {{s, s, 0}, {-s, s, 0}, {0, 0, 1}}, {1, 0.5, 0.25}};
    const auto p = ObbSlabs<double>::prepare(b);
    // Along x: enters the rotated box where |x'| <= 1 and |y'| <= 0.5 on the line y = 0: the
    // y' slab limits x to [-0.5 sqrt2, 0.5 sqrt2].
    const auto h = ObbSlabs<double>::intersect(p, Rayd{{-5, 0, 0}, {1, 0, 0}});
    REQUIRE(h);
    CHECK(h->t == Approx(5 - 0.5 / s));
    // Parallel to the z slab (dir.z == 0): inside, outside and exactly on its face planes.
    for (const double z : {0.0, 0.25, -0.25, 0.3}) {
        const Rayd r{{-5, 0, z}, {1, 0, 0}};
        const auto hz = ObbSlabs<double>::intersect(p, r);
        CHECK(hz.has_value() == (std::abs(z) <= 0.25));
        if (hz) {
            CHECK_FALSE(std::isnan(hz->t));
        }
    }
    // Origin inside: t = tmin. Pointing away from outside: miss.
    const auto hin = ObbSlabs<double>::intersect(p, Rayd{{0, 0, 0}, {0, 1, 0}, 0.5});
    REQUIRE(hin);
    CHECK(hin->t == 0.5);
    CHECK_FALSE(ObbSlabs<double>::intersect(p, Rayd{{-5, 0, 0}, {-1, 0, 0}}));
    // Bounds contain all eight corners.
    const Bounds3d bb = ObbSlabs<double>::bounds(p);
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner = b.center + b.axis[0] * ((c & 1) ? b.half.x : -b.half.x) +
                             b.axis[1] * ((c & 2) ? b.half.y : -b.half.y) +
                             b.axis[2] * ((c & 4) ? b.half.z : -b.half.z);
        CHECK(bb.contains(corner));
    }
    // Flat box (zero half extent): a ray through it hits, parallel rays in its plane hit.
    const Obb<float> flat{{0, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {1, 1, 0}};
    CHECK(ObbSlabs<float>::intersect(flat, Rayf{{0.5f, 0.5f, 1}, {0, 0, -1}}));
    CHECK(ObbSlabs<float>::intersect(flat, Rayf{{-2, 0.5f, 0}, {1, 0, 0}}));
    CHECK_FALSE(ObbSlabs<float>::intersect(flat, Rayf{{-2, 0.5f, 1e-7f}, {1, 0, 0}}));
    // Denormal direction along a slab normal: no NaN even with the origin on a face plane.
    const Rayf den{{-2, 0.5f, 0}, {1, 0, std::numeric_limits<float>::denorm_min()}};
    const auto hd = ObbSlabs<float>::intersect(flat, den);
    if (hd) {
        CHECK_FALSE(std::isnan(hd->t));
    }
}
