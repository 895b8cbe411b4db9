#pragma once
// Exact references shared by the cross-checks and the stability suite (stability/): the nearest
// root of a ray against a sphere, a triangle or a polynomial surface, decided in exact rationals
// (GMP) and evaluated with MPFR where a square root or an irrational root is needed. Inputs are
// doubles, so float inputs (exactly representable as doubles) give the answer for the float shape.

#include "intersect/cone/cone.h"
#include "intersect/implicit/torus.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"
#include "intersect/vec.h"

#include <gmpxx.h>
#include <vector>

namespace rtlab::xcheck {

/// An exact answer: whether the window [tmin, tmax] holds a root, and the smallest one (rounded
/// to double; 0 on a miss).
struct ExactRoot {
    bool hit = false;
    double t = 0;
};

/// (-b + sign * sqrt(disc)) / a for rational a != 0, b and disc >= 0: the roots of
/// a t^2 + 2 b t + c with disc = b^2 - a c, from a 256-bit MPFR square root rounded to double.
double mpfr_root(const mpq_class& a, const mpq_class& b, const mpq_class& disc, int sign);

/// Exact sphere answer: the smallest t in [tmin, tmax] (tmax may be +inf) with
/// |org + t dir - center| = radius, decided in rationals; the root itself from a 256-bit MPFR
/// square root. dir must be non-zero.
ExactRoot exact_sphere_root(const Vec3d& center, double radius, const Rayd& ray);

/// Both roots of the sphere's ray quadratic (entering <= leaving), 256-bit MPFR rounded to double;
/// false when the line misses (negative discriminant). dir must be non-zero.
bool exact_sphere_roots(
    const Vec3d& center, double radius, const Rayd& ray, double& t0, double& t1);

/// Exact cone answer: the smallest t in [tmin, tmax] (tmax may be +inf) on the lateral surface
/// (the quadric E^2 |w|^2 - E (w.e)^2 = (r0 E + (r1 - r0) w.e)^2 with w = p - base, e = apex -
/// base, E = e.e, restricted to 0 <= w.e <= E) or on a requested cap disk, decided in rationals;
/// a quadric root from a 256-bit MPFR square root. A ray lying in the surface (a generator) hits
/// at its first point on the cone. dir must be non-zero, base != apex.
ExactRoot exact_cone_root(const Cone<double>& cone, const Rayd& ray);

/// Exact ray-triangle answer (two-sided, edges inclusive) by Cramer's rule in rationals.
struct ExactTriangleHit {
    bool hit = false;       ///< the ray meets the closed triangle at one point in [tmin, tmax]
    double t = 0;           ///< that point's t, rounded to double (0 on a miss)
    bool boundary = false;  ///< undecidable by rounding-free methods: the ray meets an edge or a
                            ///< vertex exactly, or lies in the triangle's plane (det == 0)
};

/// The exact answer for one triangle (vertices and ray as given, no degeneracy handling: a
/// zero-area triangle gives det == 0, i.e. boundary and no hit).
ExactTriangleHit exact_triangle_hit(const Triangled& tri, const Rayd& ray);

/// Exact first root of the polynomial p (ascending rational coefficients) in [tmin, tmax]
/// (tmax may be +inf): distinct roots counted by a Sturm sequence over Q, the smallest isolated
/// by Sturm bisection, refined by 256-bit MPFR bisection to < 2^-110 relative.
ExactRoot exact_first_root(std::vector<mpq_class> p, double tmin, double tmax);

/// The exact ray polynomial of a torus: Torus::along expanded over Q.
std::vector<mpq_class> exact_torus_along(const Torus<double>& s, const Vec3d& o, const Vec3d& d);

}  // namespace rtlab::xcheck
