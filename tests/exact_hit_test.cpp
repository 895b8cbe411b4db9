// Certified ray/triangle hits (intersect/triangle/exact_hit.h) against CGAL's exact kernel as an
// independent oracle (crosscheck/exact_triangle_oracle.h, which keeps CGAL inside the crosscheck
// library): hit or miss, t the nearest float to the exact t, and the closest primitive under the
// lowest-id tie rule, on random rays, rays aimed exactly at lattice vertices and shared edges at
// three scales, a perturbed closed sphere, grazing and coplanar rays, axis-aligned rays and
// origins on the surface. The plain watertight float test is scored on the same rays.

#include "intersect/triangle/exact_hit.h"

#include "crosscheck/exact_triangle_oracle.h"
#include "intersect/triangle/sphere_mesh.h"
#include "intersect/triangle/watertight.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace rtlab;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

/// True when f is the float nearest to the oracle's exact t (ties to even). The oracle rounds its
/// exact t itself, and the nearest float is unique, so this is float equality; a non-finite f is
/// never right.
bool is_nearest(float f, float oracle_t) {
    return std::isfinite(f) && f == oracle_t;
}

/// One ray set: a triangle list (ids are indices) and its rays.
struct RaySet {
    std::string name;
    std::vector<Trianglef> tris;
    std::vector<Rayf> rays;
};

/// Agreement counts for one set: the certified test must have no disagreement; the plain
/// watertight float test's errors are only reported.
struct Score {
    std::size_t rays = 0, pairs = 0, fallbacks = 0;
    std::size_t pair_errors = 0, closest_errors = 0;    // certified test vs the oracle
    std::size_t wt_pair_errors = 0, wt_hit_errors = 0;  // watertight: per pair; closest hit/miss
    std::size_t wt_prim_errors = 0, wt_t_errors = 0;    // watertight: closest prim; t not nearest
    std::string first_error;
};

/// The closest hit of each kind for one ray, brute force over the set.
struct Closest {
    std::uint32_t oracle_id = invalid_id, exact_id = invalid_id, wt_id = invalid_id;
    float oracle_t = inf;  ///< the oracle's closest t, rounded to nearest
    ExactHit exact;
    float wt_t = inf;
};

void note(Score& s, const RaySet& set, std::size_t ray, std::uint32_t prim, const char* what) {
    if (s.first_error.empty()) {
        std::ostringstream os;
        os << set.name << ": ray " << ray << " prim " << prim << ": " << what;
        s.first_error = os.str();
    }
}

/// Tests one ray against every triangle of the set, pair by pair and for the closest hit.
void score_ray(const RaySet& set, std::size_t i, Score& s) {
    using Wt = Watertight<float>;
    const Rayf& ray = set.rays[i];
    const xcheck::ExactTriangleHits oracle = xcheck::exact_triangle_hits(set.tris, ray);
    const Wt::RayData wrd = Wt::precompute(ray);
    Closest c;
    c.oracle_id = oracle.closest;
    if (c.oracle_id != invalid_id) {
        c.oracle_t = oracle.pairs[c.oracle_id].t;
    }
    for (std::uint32_t id = 0; id < set.tris.size(); ++id) {
        const Trianglef& tri = set.tris[id];
        const xcheck::ExactPairHit& o = oracle.pairs[id];
        const ExactHit h = exact_intersect(ray, tri.p0, tri.p1, tri.p2);
        const auto w = Wt::intersect(Wt::prepare(tri), ray, wrd);
        ++s.pairs;
        s.fallbacks += h.fallback ? 1 : 0;
        if (h.hit != o.hit || (o.hit && !is_nearest(h.t, o.t))) {
            ++s.pair_errors;
            note(s, set, i, id, h.hit != o.hit ? "hit/miss" : "t not nearest");
        }
        if (w.has_value() != o.hit || (o.hit && !is_nearest(w->t, o.t))) {
            ++s.wt_pair_errors;
        }
        if (h.hit && (c.exact_id == invalid_id ||
                      exact_less(ray, h, tri, id, c.exact, set.tris[c.exact_id], c.exact_id))) {
            c.exact_id = id;
            c.exact = h;
        }
        if (w && w->t < c.wt_t) {
            c.wt_id = id;
            c.wt_t = w->t;
        }
    }
    if (c.exact_id != c.oracle_id) {
        ++s.closest_errors;
        note(s, set, i, c.exact_id, "closest primitive");
    }
    const bool oracle_hit = c.oracle_id != invalid_id;
    s.wt_hit_errors += (c.wt_id != invalid_id) != oracle_hit ? 1 : 0;
    s.wt_prim_errors += oracle_hit && c.wt_id != invalid_id && c.wt_id != c.oracle_id ? 1 : 0;
    s.wt_t_errors += oracle_hit && c.wt_id != invalid_id && !is_nearest(c.wt_t, c.oracle_t) ? 1 : 0;
}

/// Scores a whole set, reports its counts once and requires full agreement.
void check_set(const RaySet& set) {
    Score s;
    s.rays = set.rays.size();
    for (std::size_t i = 0; i < set.rays.size(); ++i) {
        score_ray(set, i, s);
    }
    INFO(set.name << ": " << s.rays << " rays, " << s.pairs << " pairs, " << s.fallbacks
                  << " exact fallbacks; watertight float: " << s.wt_pair_errors
                  << " pairs wrong, closest " << s.wt_hit_errors << " hit/miss, "
                  << s.wt_prim_errors << " primitive, " << s.wt_t_errors << " t not nearest");
    INFO(s.first_error);
    CHECK(s.rays > 0);
    CHECK(s.pair_errors == 0);
    CHECK(s.closest_errors == 0);
}

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(std::uint64_t seed) : gen(seed) {}
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(gen() >> 11) * 0x1.0p-53;
    }
    int integer(int lo, int hi) { return lo + static_cast<int>(gen() % (hi - lo + 1)); }
    float f(double lo, double hi) { return static_cast<float>(uniform(lo, hi)); }
    Vec3f vec(double lo, double hi) { return {f(lo, hi), f(lo, hi), f(lo, hi)}; }
};

/// Windows cycled over a set's rays: open, [0, 1] (1 is the aimed point's t in the lattice
/// sets), [1, inf), the single point [1, 1], and [0, just below 1].
Rayf with_window(Vec3f org, Vec3f dir, std::size_t k) {
    constexpr float below_one = 0x1.fffffep-1f;
    const float tmins[] = {0.0f, 0.0f, 1.0f, 1.0f, 0.0f};
    const float tmaxs[] = {inf, 1.0f, inf, 1.0f, below_one};
    return {org, dir, tmins[k % 5], tmaxs[k % 5]};
}

/// Random triangles in [-1, 1]^3, a few repeated at the end (exact ties), and random rays with
/// random windows.
RaySet random_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"random", {}, {}};
    for (int i = 0; i < 48; ++i) {
        set.tris.push_back({rng.vec(-1, 1), rng.vec(-1, 1), rng.vec(-1, 1)});
    }
    for (int i = 0; i < 4; ++i) {
        set.tris.push_back(set.tris[static_cast<std::size_t>(i) * 5]);
    }
    for (int i = 0; i < 1000; ++i) {
        const float tmin = i % 3 == 0 ? rng.f(-1, 1) : 0.0f;
        const float tmax = i % 4 == 0 ? rng.f(0, 4) : inf;
        set.rays.push_back({rng.vec(-2, 2), rng.vec(-1, 1), tmin, tmax});
    }
    return set;
}

/// Random triangles in [-1, 1]^3 seen from origins about 2^30 away, aimed exactly through the
/// centre (dir = -org): the vertices' offsets from the origin are not exact in double.
RaySet far_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"far origins", random_set(seed).tris, {}};
    for (int i = 0; i < 300; ++i) {
        Vec3f org = rng.vec(0x1.0p30, 0x1.0p31);
        for (std::size_t k = 0; k < 3; ++k) {
            org[k] = rng.integer(0, 1) == 0 ? -org[k] : org[k];
        }
        set.rays.push_back({org, -org, 0.0f, inf});
    }
    return set;
}

/// Integer height of the lattice terrain at (i, j): a few slopes, so edges are not all level.
int height(int i, int j) {
    return (i * j + i) % 3 - 1;
}

/// An n x n lattice terrain scaled by s (a power of two: every vertex and edge midpoint is exact),
/// two triangles per cell split along the (i, j)-(i+1, j+1) diagonal.
std::vector<Trianglef> lattice(int n, float s) {
    std::vector<Trianglef> tris;
    const auto p = [&](int i, int j) {
        return Vec3f{static_cast<float>(i) * s, static_cast<float>(j) * s,
                     static_cast<float>(height(i, j)) * s};
    };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            tris.push_back({p(i, j), p(i + 1, j), p(i + 1, j + 1)});
            tris.push_back({p(i, j), p(i + 1, j + 1), p(i, j + 1)});
        }
    }
    return tris;
}

/// Every vertex and every edge midpoint of the lattice terrain (exact floats).
std::vector<Vec3f> lattice_targets(int n, float s) {
    std::vector<Vec3f> out;
    const auto p = [&](double i, double j, double h) {
        return Vec3f{static_cast<float>(i) * s, static_cast<float>(j) * s,
                     static_cast<float>(h) * s};
    };
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            out.push_back(p(i, j, height(i, j)));
            if (i < n) {
                out.push_back(p(i + 0.5, j, 0.5 * (height(i, j) + height(i + 1, j))));
            }
            if (j < n) {
                out.push_back(p(i, j + 0.5, 0.5 * (height(i, j) + height(i, j + 1))));
            }
            if (i < n && j < n) {
                out.push_back(p(i + 0.5, j + 0.5, 0.5 * (height(i, j) + height(i + 1, j + 1))));
            }
        }
    }
    return out;
}

/// Rays aimed exactly at lattice vertices and edge midpoints (origin = target + offset, dir =
/// -offset, both exact, so the target is at t = 1), plus rays from random float origins whose
/// rounded direction passes near the target.
RaySet lattice_set(std::uint64_t seed, float s) {
    Rng rng(seed);
    constexpr int n = 4;
    RaySet set{"lattice s=" + std::to_string(s), lattice(n, s), {}};
    std::size_t k = 0;
    for (const Vec3f& t : lattice_targets(n, s)) {
        for (int rep = 0; rep < 2; ++rep) {
            const Vec3f off{static_cast<float>(rng.integer(-3, 3)) * s,
                            static_cast<float>(rng.integer(-3, 3)) * s,
                            static_cast<float>(rng.integer(1, 5)) * s};
            set.rays.push_back(with_window(t + off, -off, k++));
        }
        const Vec3f org = rng.vec(-1, 5) * s + Vec3f{0, 0, 3 * s};
        set.rays.push_back({org, t - org, 0.0f, inf});
    }
    return set;
}

/// Axis-aligned rays at the lattice targets: straight down and up (two zero components), along
/// x and y at the target's height (grazing the terrain), diagonal in xz and yz (one zero), and
/// down with a denormal x component.
RaySet axis_set(float s) {
    constexpr int n = 4;
    RaySet set{"axis-aligned s=" + std::to_string(s), lattice(n, s), {}};
    const Vec3f dirs[] = {{0, 0, -1}, {0, 0, 1},   {1, 0, 0},           {0, -1, 0},
                          {1, 0, -1}, {0, -1, -1}, {0x1.0p-140f, 0, -1}};  // a denormal component
    std::size_t k = 0;
    for (const Vec3f& t : lattice_targets(n, s)) {
        for (const Vec3f& d : dirs) {
            const Vec3f dir = d * s;
            set.rays.push_back(with_window(t - dir * 2.0f, dir * 2.0f, k++));
        }
    }
    return set;
}

/// The perturbed closed sphere: rays from the centre aimed exactly at every vertex (the origin
/// is 0, so dir = vertex is exact), near edge midpoints, and from random inner points.
RaySet sphere_set(std::uint64_t seed) {
    Rng rng(seed);
    const IndexedMesh mesh = perturbed_sphere_mesh(seed, 8, 12);
    RaySet set{"sphere", {}, {}};
    for (const auto& f : mesh.faces) {
        set.tris.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
    }
    for (const Vec3f& v : mesh.vertices) {
        set.rays.push_back({{0, 0, 0}, v, 0.0f, inf});
        set.rays.push_back({{0, 0, 0}, v, 0.0f, 1.0f});  // the vertex at t = 1 exactly
    }
    for (std::size_t i = 0; i < 120; ++i) {
        const auto& f = mesh.faces[i % mesh.faces.size()];
        const Vec3f mid = (mesh.vertices[f[0]] + mesh.vertices[f[1]]) * 0.5f;
        const Vec3f org = i % 2 == 0 ? Vec3f{0, 0, 0} : rng.vec(-0.3, 0.3);
        set.rays.push_back({org, mid - org, 0.0f, inf});
    }
    return set;
}

/// The perturbed sphere with vertices on the 2^-20 grid, so that sums stay exact floats: rays
/// from grid points inside aimed exactly at every vertex (dir = v - org) and at every edge's
/// midpoint (dir = v_i + v_j - 2 org, the midpoint at t = 1/2). Products of three coordinates
/// need more than 53 bits here, so the double filter rounds.
RaySet quantized_sphere_set(std::uint64_t seed) {
    Rng rng(seed);
    IndexedMesh mesh = perturbed_sphere_mesh(seed, 8, 12);
    const auto grid = [](float x) { return std::round(x * 0x1.0p20f) * 0x1.0p-20f; };
    for (Vec3f& v : mesh.vertices) {
        v = {grid(v.x), grid(v.y), grid(v.z)};
    }
    RaySet set{"quantized sphere", {}, {}};
    for (const auto& f : mesh.faces) {
        set.tris.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
    }
    const auto org = [&] {
        const Vec3f o = rng.vec(-0.25, 0.25);
        return Vec3f{grid(o.x), grid(o.y), grid(o.z)};
    };
    for (const Vec3f& v : mesh.vertices) {
        const Vec3f o = org();
        set.rays.push_back({o, v - o, 0.0f, inf});
    }
    for (const auto& f : mesh.faces) {
        const Vec3f o = org();
        const Vec3f vi = mesh.vertices[f[0]], vj = mesh.vertices[f[1]];
        set.rays.push_back({o, vi + vj - o * 2.0f, 0.0f, inf});
    }
    return set;
}

/// Integer triangles in tilted planes with rays lying exactly in a triangle's plane (origin and
/// direction integer combinations of its edges: coplanar, a miss by rule), and the same rays with
/// the direction or the origin moved by one ulp in one component (grazing).
RaySet grazing_set(std::uint64_t seed) {
    Rng rng(seed);
    RaySet set{"grazing", {}, {}};
    const auto ivec = [&] {
        return Vec3f{static_cast<float>(rng.integer(-8, 8)), static_cast<float>(rng.integer(-8, 8)),
                     static_cast<float>(rng.integer(-8, 8))};
    };
    while (set.tris.size() < 16) {
        const Trianglef t{ivec(), ivec(), ivec()};
        if (!is_degenerate(t.p0, t.p1, t.p2)) {
            set.tris.push_back(t);
        }
    }
    for (const Trianglef& t : set.tris) {
        const Vec3f e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
        for (int r = 0; r < 6; ++r) {
            const auto a = static_cast<float>(rng.integer(-2, 2));
            const auto b = static_cast<float>(rng.integer(-2, 2));
            const Vec3f org = t.p0 + e1 * a + e2 * b;
            Vec3f dir = e1 * static_cast<float>(rng.integer(-2, 2)) +
                        e2 * static_cast<float>(rng.integer(-2, 2));
            if (dir == Vec3f{0, 0, 0}) {
                dir = t.p2 - t.p1;
            }
            const auto axis = static_cast<std::size_t>(r % 3);
            Vec3f dir_ulp = dir, org_ulp = org;
            dir_ulp[axis] = std::nextafter(dir[axis], r < 3 ? inf : -inf);
            org_ulp[axis] = std::nextafter(org[axis], r < 3 ? -inf : inf);
            set.rays.push_back({org, dir, -inf, inf});
            set.rays.push_back({org, dir_ulp, -inf, inf});
            set.rays.push_back({org_ulp, dir, -inf, inf});
        }
    }
    return set;
}

/// Origins on the lattice surface (vertices, edge midpoints, and points inside triangles with
/// dyadic barycentrics), random directions, windows starting at 0 (so t = 0 is a hit).
RaySet surface_set(std::uint64_t seed, float s) {
    Rng rng(seed);
    constexpr int n = 4;
    RaySet set{"surface origins s=" + std::to_string(s), lattice(n, s), {}};
    std::vector<Vec3f> origins = lattice_targets(n, s);
    for (const Trianglef& t : set.tris) {
        origins.push_back(t.p0 + (t.p1 - t.p0) * 0.25f + (t.p2 - t.p0) * 0.5f);
    }
    for (const Vec3f& o : origins) {
        set.rays.push_back({o, rng.vec(-1, 1) * s, 0.0f, inf});
    }
    return set;
}

}  // namespace

TEST_CASE("certified hits agree with CGAL on random, far, sphere and grazing rays", "[exact]") {
    check_set(random_set(11));
    check_set(far_set(13));
    check_set(sphere_set(31));
    check_set(quantized_sphere_set(37));
    check_set(grazing_set(41));
}

TEST_CASE("certified hits agree with CGAL on lattice, axis-aligned and surface rays at 3 scales",
          "[exact]") {
    const float s = GENERATE(1.0f, 0x1.0p-20f, 0x1.0p20f);
    check_set(lattice_set(21, s));
    check_set(axis_set(s));
    check_set(surface_set(51, s));
}

TEST_CASE("certified hits round t to nearest and break exact ties by the lowest id", "[exact]") {
    // Two triangles sharing the edge x = 1 of the plane z = 3; a ray down onto that edge.
    const Trianglef a{{0, 0, 3}, {1, 0, 3}, {1, 1, 3}}, b{{1, 0, 3}, {2, 0, 3}, {1, 1, 3}};
    const Rayf ray{{1, 0.5f, 0}, {0, 0, 1}, 0.0f, inf};
    const ExactHit ha = exact_intersect(ray, a.p0, a.p1, a.p2);
    const ExactHit hb = exact_intersect(ray, b.p0, b.p1, b.p2);
    REQUIRE(ha.hit);
    REQUIRE(hb.hit);
    CHECK(ha.t == 3.0f);
    CHECK(hb.t == 3.0f);
    CHECK(exact_less(ray, ha, a, 4, hb, b, 7));
    CHECK_FALSE(exact_less(ray, hb, b, 7, ha, a, 4));
    CHECK(exact_less(ray, hb, b, 2, ha, a, 4));
    // t = 1/3 exactly: the nearest float, not a truncation.
    const Rayf third{{0.25f, 0.25f, 0}, {0, 0, 9}, 0.0f, inf};
    const ExactHit h3 = exact_intersect(third, a.p0, a.p1, a.p2);
    REQUIRE(h3.hit);
    CHECK(h3.t == 1.0f / 3.0f);
}

TEST_CASE("certified hits order distinct exact t that round to one float", "[exact]") {
    // Planes z = 3 and z = 3 + 2^-22 seen from z = -2^-22 along (0, 0, 3): t = 1 + 2^-22 / 3 and
    // 1 + 2^-21 / 3 both round to 1 + 2^-23, so only the exact comparison orders them.
    const float h = 3.0f + 0x1.0p-22f;
    const Trianglef near{{0, 0, 3}, {1, 0, 3}, {0, 1, 3}}, far{{0, 0, h}, {1, 0, h}, {0, 1, h}};
    const Rayf ray{{0.25f, 0.25f, -0x1.0p-22f}, {0, 0, 3}, 0.0f, inf};
    const ExactHit hn = exact_intersect(ray, near.p0, near.p1, near.p2);
    const ExactHit hf = exact_intersect(ray, far.p0, far.p1, far.p2);
    REQUIRE(hn.hit);
    REQUIRE(hf.hit);
    CHECK(hn.t == hf.t);
    CHECK(exact_less(ray, hn, near, 9, hf, far, 1));  // smaller t wins over the lower id
    CHECK_FALSE(exact_less(ray, hf, far, 1, hn, near, 9));
    CHECK(exact_compare_t(ray, near, far) == -1);
    CHECK(exact_compare_t(ray, far, far) == 0);
}

TEST_CASE("certified hits round t at and next to a midpoint between floats", "[exact]") {
    // Plane z = 3 + 2^-22, dir (0, 0, 3): t = (3 + 2^-22 - oz) / 3. With oz = 2^-24, t is exactly
    // 1 + 2^-24, halfway between 1 and 1 + 2^-23 (ties to even: 1); one float of oz either way
    // moves t just above or below the midpoint.
    const float h = 3.0f + 0x1.0p-22f;
    const Trianglef tri{{0, 0, h}, {1, 0, h}, {0, 1, h}};
    const auto t_for = [&](float oz) {
        const ExactHit hit =
            exact_intersect({{0.25f, 0.25f, oz}, {0, 0, 3}, 0.0f, inf}, tri.p0, tri.p1, tri.p2);
        REQUIRE(hit.hit);
        return hit;
    };
    const ExactHit mid = t_for(0x1.0p-24f);
    CHECK(mid.t == 1.0f);
    CHECK(mid.fallback);  // a tie cannot be certified by the double enclosure
    CHECK(t_for(std::nextafter(0x1.0p-24f, 0.0f)).t == 1.0f + 0x1.0p-23f);
    CHECK(t_for(std::nextafter(0x1.0p-24f, 1.0f)).t == 1.0f);
}
