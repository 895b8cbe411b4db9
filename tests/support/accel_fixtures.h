#pragma once
// Seeded random primitive soups and ray sets for acceleration-structure tests. A soup holds
// either axis-aligned boxes (a box is hit at its slab entry t) or Möller–Trumbore triangles,
// plus one bounding box per primitive, and hands out the leaf callbacks traversal needs. Soups
// include duplicates, flat and point boxes or zero-area triangles; rays include axis-aligned
// directions, origins inside the scene and on primitive faces (node boundaries), and tight
// windows.

#include "accel/accel.h"
#include "intersect/box/slabs.h"
#include "intersect/hit.h"
#include "intersect/triangle/moller_trumbore.h"
#include "trace/clip.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace rtlab::test {

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny PRNG whose output is the same on every platform
/// and standard library, unlike std::uniform_real_distribution.
class Rng {
public:
    /// A generator seeded with `seed`.
    explicit Rng(std::uint64_t seed) : state_(seed) {}

    /// Next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform float in [0, 1) with 24 random bits.
    float uniform() { return static_cast<float>(next() >> 40) * 0x1.0p-24f; }
    /// Uniform float in [lo, hi).
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform integer in [0, n) for n >= 1.
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(next() % n); }
    /// Uniform point in the box b.
    Vec3f point_in(const Bounds3f& b) {
        return {uniform(b.lo.x, b.hi.x), uniform(b.lo.y, b.hi.y), uniform(b.lo.z, b.hi.z)};
    }
    /// Direction uniform on the unit sphere.
    Vec3f direction() {
        for (;;) {
            const Vec3f d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const float l2 = length_squared(d);
            if (l2 > 0.01f && l2 <= 1.0f) {
                return d / std::sqrt(l2);
            }
        }
    }

private:
    std::uint64_t state_;
};

/// Which primitives a soup holds.
enum class SoupKind { boxes, triangles };

/// A primitive soup: the primitives, one bounding box per primitive (index = id), and the leaf
/// callbacks. Box primitives that fail is_usable_box never hit.
struct Soup {
    SoupKind kind = SoupKind::boxes;
    std::vector<Bounds3f> boxes;                             ///< bounds of each primitive
    std::vector<MollerTrumbore<float>::Prepared> triangles;  ///< triangles (kind == triangles)

    /// What a builder receives: the boxes, and the triangles' exact extents.
    BuildInput input() const {
        ExtentFn extent;
        if (kind == SoupKind::triangles) {
            extent = [this](std::uint32_t id, const Vec3f& d) {
                const auto& t = triangles[id];
                return shape_extent(Triangle<float>{t.p0, t.p1, t.p2}, d);
            };
        }
        return {boxes, {}, extent};
    }

    /// The exact primitive test: boxes are hit at the slab entry clipped to [tmin, tmax].
    std::optional<PrimHit<float>> hit(std::uint32_t id, const Rayf& ray) const {
        if (kind == SoupKind::triangles) {
            return MollerTrumbore<float>::intersect(triangles[id], ray);
        }
        const Bounds3f& b = boxes[id];
        if (!is_usable_box(b)) {
            return std::nullopt;  // empty, NaN or infinite: not a primitive
        }
        float t0 = ray.tmin, t1 = ray.tmax;
        if (!clip_slabs<false>(b.lo, b.hi, SlabRay<float>(ray), t0, t1)) {
            return std::nullopt;
        }
        return PrimHit<float>{t0};
    }

    /// Closest-hit callback recording into h and shrinking ray.tmax.
    auto closest_hit(Hit& h) const {
        return [this, &h](std::uint32_t id, Rayf& ray) {
            const std::optional<PrimHit<float>> ph = hit(id, ray);
            if (!ph) {
                return false;
            }
            h = {ph->t, ph->u, ph->v, id};
            ray.tmax = ph->t;
            return true;
        };
    }

    /// Any-hit callback.
    auto any_hit() const {
        return [this](std::uint32_t id, const Rayf& ray) { return hit(id, ray).has_value(); };
    }

    /// Union of the usable primitive boxes.
    Bounds3f scene_bounds() const {
        Bounds3f s;
        for (const Bounds3f& b : boxes) {
            if (is_usable_box(b)) {
                s.extend(b);
            }
        }
        return s;
    }
};

/// `count` primitives in about [0, 1]^3, sized so the soup is moderately overlapping. About 1 in
/// 16 primitives duplicates the previous one, 1 in 16 is flat (box: zero extent on one axis;
/// triangle: in an axis plane) and 1 in 32 is a point box or a zero-area triangle.
inline Soup random_soup(SoupKind kind, std::uint64_t seed, std::uint32_t count) {
    Rng rng(seed * 0x2545F4914F6CDD1Dull + count);
    Soup s;
    s.kind = kind;
    const float size = 1.5f / std::cbrt(static_cast<float>(std::max(count, 1u)));
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t special = rng.below(32);
        if (special < 2 && i > 0) {
            s.boxes.push_back(s.boxes.back());
            if (kind == SoupKind::triangles) {
                s.triangles.push_back(s.triangles.back());
            }
            continue;
        }
        const Vec3f c = rng.point_in({{0, 0, 0}, {1, 1, 1}});
        if (kind == SoupKind::boxes) {
            Vec3f h{rng.uniform(0, size), rng.uniform(0, size), rng.uniform(0, size)};
            if (special == 2 || special == 3) {
                h[rng.below(3)] = 0;
            } else if (special == 4) {
                h = {0, 0, 0};
            }
            s.boxes.emplace_back(c - h, c + h);
            continue;
        }
        Trianglef t{c + rng.direction() * size, c + rng.direction() * size,
                    c + rng.direction() * size};
        if (special == 2 || special == 3) {
            const std::size_t a = rng.below(3);
            t.p1[a] = t.p0[a];
            t.p2[a] = t.p0[a];
        } else if (special == 4) {
            t.p2 = t.p0 + (t.p1 - t.p0) * 0.5f;  // collinear (up to rounding)
        }
        s.triangles.push_back(MollerTrumbore<float>::prepare(t));
        s.boxes.push_back(MollerTrumbore<float>::bounds(s.triangles.back()));
    }
    return s;
}

/// Boxes on the 4 x 4 x 4 unit lattice over [0, 4]^3: a unit box at each cell corner c with
/// x + y + z even; where it is odd, two duplicate flat boxes [c, c + flat] in the layer z = 1 and
/// a point box at c elsewhere. Every face and point lies on a lattice plane.
inline Soup lattice_soup(const Vec3f& flat) {
    Soup soup;
    for (int x = 0; x < 4; ++x) {
        for (int y = 0; y < 4; ++y) {
            for (int z = 0; z < 4; ++z) {
                const Vec3f c{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
                if ((x + y + z) % 2 == 0) {
                    soup.boxes.push_back({c, c + Vec3f{1, 1, 1}});
                } else if (z == 1) {
                    soup.boxes.push_back({c, c + flat});
                    soup.boxes.push_back(soup.boxes.back());
                } else {
                    soup.boxes.push_back(Bounds3f(c));
                }
            }
        }
    }
    return soup;
}

/// A triangle soup where a near hit lies beyond the first cell or leaf of a long primitive, for
/// the ray from (-1, 0.5, 0.5) along +x: L (id 0), a long slanted triangle spanning x in [0, 10]
/// that the ray hits at x = 9; S (id 1), a small triangle on the ray at x = s_x; and 40 filler
/// triangles along x, off the ray, that force cells or splits along it.
inline Soup long_primitive_soup(float s_x) {
    Soup soup;
    soup.kind = SoupKind::triangles;
    const auto add = [&](Vec3f a, Vec3f b, Vec3f c) {
        soup.triangles.push_back(MollerTrumbore<float>::prepare({a, b, c}));
        soup.boxes.push_back(MollerTrumbore<float>::bounds(soup.triangles.back()));
    };
    add({0, -1, -0.625f}, {0, 2, -0.625f}, {10, 0.5f, 0.625f});  // L, id 0
    add({s_x, 0, 0}, {s_x, 1, 0}, {s_x, 0.5f, 1});               // S, id 1
    for (int i = 0; i < 40; ++i) {
        const float x = 0.25f * static_cast<float>(i);
        add({x, 1.8f, 0.6f}, {x + 0.1f, 1.9f, 0.6f}, {x, 1.9f, 0.62f});
    }
    return soup;
}

/// `count` rays for the soup s, cycling through: from outside towards the scene, from inside the
/// scene box, axis-aligned (two zero direction components), one zero component, from a point on
/// a primitive box face (a node boundary) along that face or off it, and tight or degenerate
/// windows [tmin, tmax].
inline std::vector<Rayf> random_rays(const Soup& s, std::uint64_t seed, std::uint32_t count) {
    Rng rng(seed ^ 0xA5A5A5A5DEADBEEFull);
    Bounds3f scene = s.scene_bounds();
    if (scene.empty()) {
        scene = {{0, 0, 0}, {1, 1, 1}};
    }
    const Vec3f pad = (scene.diagonal() + Vec3f{0.1f, 0.1f, 0.1f}) * 0.5f;
    const Bounds3f outer{scene.lo - pad, scene.hi + pad};
    std::vector<Rayf> rays;
    rays.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        Rayf r;
        switch (i % 8) {
        case 0: {  // from the padded box towards a point of the scene
            r.org = rng.point_in(outer);
            r.dir = rng.point_in(scene) - r.org;
            if (length_squared(r.dir) == 0.0f) {
                r.dir = rng.direction();
            }
            break;
        }
        case 1:  // inside the scene box
            r.org = rng.point_in(scene);
            r.dir = rng.direction();
            break;
        case 2: {  // axis-aligned
            r.org = rng.point_in(scene);
            r.dir[rng.below(3)] = rng.below(2) ? 1.0f : -1.0f;
            break;
        }
        case 3: {  // one zero component
            r.org = rng.point_in(outer);
            r.dir = rng.direction();
            r.dir[rng.below(3)] = 0;
            break;
        }
        case 4:
        case 5: {  // origin on a face plane of a primitive box, along the face or off it
            const Bounds3f b = s.boxes.empty()
                                   ? scene
                                   : s.boxes[rng.below(static_cast<std::uint32_t>(s.boxes.size()))];
            const std::size_t a = rng.below(3);
            r.org = rng.point_in(scene);
            if (b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z) {
                r.org = rng.point_in(b);
                r.org[a] = rng.below(2) ? b.lo[a] : b.hi[a];
            }
            r.dir = rng.direction();
            if (i % 8 == 4) {
                r.dir[a] = 0;
            }
            break;
        }
        case 6: {  // tight window around a random t
            r.org = rng.point_in(outer);
            r.dir = rng.point_in(scene) - r.org;
            const float t = rng.uniform(0.0f, 1.2f);
            const float w = rng.below(4) == 0 ? 0.0f : rng.uniform(0.0f, 0.05f);
            r.tmin = t - w;
            r.tmax = t + w;
            break;
        }
        default: {  // finite window that may start behind the origin
            r.org = rng.point_in(scene);
            r.dir = rng.direction();
            r.tmin = rng.uniform(-0.5f, 0.2f);
            r.tmax = r.tmin + rng.uniform(0.0f, 1.0f);
            break;
        }
        }
        if (length_squared(r.dir) == 0.0f) {
            r.dir = {1, 0, 0};
        }
        rays.push_back(r);
    }
    return rays;
}

/// Counters of one closest-hit query per ray of rays on accel (any structure with the Accel
/// query API), each ray starting from its own full window.
template <class A>
TraversalStats closest_hit_stats(const A& accel, const Soup& soup, const std::vector<Rayf>& rays) {
    TraversalStats st;
    for (Rayf r : rays) {
        Hit h;
        accel.intersect(r, soup.closest_hit(h), st);
    }
    return st;
}

}  // namespace rtlab::test
