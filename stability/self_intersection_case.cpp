// Self-intersection of secondary rays: from a hit point on a triangle or a sphere (coordinates and
// sizes log-uniform in 1e-8 .. 1e8), a reflected ray and a shadow ray towards a random point on
// the outside must not hit the surface they leave, for each offset policy of trace/offset.h
// (none, epsilon = default_offset_epsilon, ulp = Wächter & Binder 2019). Named sub-case: the sphere
// flake's tangent contacts (child on parent, root on floor) of gen::generate("flake").
#include "datasets_gen/generators.h"
#include "datasets_gen/sphere_flake.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"
#include "trace/offset.h"

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rtlab::stab {

namespace {

constexpr std::array<OffsetPolicy, 3> policies{OffsetPolicy::none, OffsetPolicy::epsilon,
                                               OffsetPolicy::ulp};

/// Where the secondary rays of one sample start: the primary hit point, the unit normal on the
/// side the primary came from (the outside), the reflected direction and a shadow target on the
/// outside. `stratum` is 0 when 1 <= |c| / size <= 1e4 (c: the shape's centre, size: triangle
/// size or sphere radius), else 1.
template <class T>
struct Start {
    std::uint32_t shape = 0;
    Vec3<T> p, n, reflect, target;
    int stratum = 0;
};

/// v turned into the hemisphere around n (n unit): mirrored in the plane normal to n when it
/// points away from n.
Vec3d into_hemisphere(const Vec3d& v, const Vec3d& n) {
    return dot(v, n) < 0 ? v - n * (2 * dot(v, n)) : v;
}

/// A unit vector in the hemisphere around n (n unit).
Vec3d hemisphere(Sampler& rng, const Vec3d& n) {
    return into_hemisphere(rng.unit(), n);
}

/// d reflected in the plane with unit normal n.
template <class T>
Vec3<T> reflect(const Vec3<T>& d, const Vec3<T>& n) {
    return d - n * (T(2) * dot(d, n));
}

/// True when both secondary directions leave the surface decisively (cosine with the normal at
/// least 1e-2): otherwise rounding of the direction or of the shadow target alone could send the
/// ray back through the surface, which would not be a self-intersection.
template <class T>
bool decisive(const Start<T>& s) {
    const Vec3d n(s.n);
    return dot(normalize(Vec3d(s.reflect)), n) >= 1e-2 &&
           dot(normalize(Vec3d(s.target) - Vec3d(s.p)), n) >= 1e-2;
}

/// The decisive starts of some samples, and how many samples gave none.
template <class T>
struct Starts {
    std::vector<Start<T>> starts;
    std::size_t missed = 0;   ///< the primary ray missed (or its hit point has no normal)
    std::size_t grazing = 0;  ///< not decisive
};

/// The starts of samples 0 .. n-1: start_of(i) gives sample i's start, or nothing when its
/// primary ray missed; starts that are not decisive are counted and left out.
template <class T, class StartOf>
Starts<T> collect_starts(std::size_t n, const StartOf& start_of) {
    Starts<T> out;
    for (std::size_t i = 0; i < n; ++i) {
        const std::optional<Start<T>> s = start_of(i);
        if (!s) {
            ++out.missed;
        } else if (!decisive(*s)) {
            ++out.grazing;
        } else {
            out.starts.push_back(*s);
        }
    }
    return out;
}

/// "<m> primary misses and <g> grazing starts skipped", with `also` (if any) among them.
template <class T>
std::string skipped_note(const Starts<T>& k, const std::string& also = {}) {
    const std::string misses = std::to_string(k.missed) + " primary misses";
    const std::string grazing = std::to_string(k.grazing) + " grazing starts";
    return (also.empty() ? misses + " and " + grazing : misses + ", " + grazing + " and " + also) +
           " skipped";
}

/// self_hit for policy_rows: method M's any-hit test against the start's own shape.
template <class M>
auto own_shape_hit(const std::vector<typename M::Prepared>& prep) {
    return [&prep](std::uint32_t shape, const auto& ray) { return M::occluded(prep[shape], ray); };
}

/// Secondary rays of the start in precision T under a policy: the reflected ray ([0, inf)) and the
/// shadow ray to the target ([0, 1]).
template <class T>
std::array<Ray<T>, 2> secondaries(const Start<T>& s, OffsetPolicy policy) {
    const Vec3<T> o = offset_origin(s.p, s.n, policy, static_cast<T>(default_offset_epsilon));
    return {Ray<T>{o, s.reflect}, Ray<T>{o, s.target - o, T(0), T(1)}};
}

/// One row per policy: re-intersections of the starting surface (self_hit(shape, ray)), split
/// into reflection and shadow rays and by stratum in the note; `stratified` adds a row per policy
/// for stratum 0 alone ("1<=|c|/size<=1e4").
template <class T, class SelfHit>
void policy_rows(const std::vector<Start<T>>& starts,
                 const SelfHit& self_hit,
                 const std::string& case_name,
                 const std::string& label,
                 const std::string& extra_note,
                 bool stratified,
                 std::vector<Row>& rows) {
    for (OffsetPolicy policy : policies) {
        std::array<std::size_t, 2> n_stratum{}, fail_stratum{};
        std::size_t fail_reflect = 0, fail_shadow = 0;
        const Stopwatch sw;
        for (const Start<T>& s : starts) {
            const std::array<Ray<T>, 2> rays = secondaries(s, policy);
            const bool r = self_hit(s.shape, rays[0]);
            const bool sh = self_hit(s.shape, rays[1]);
            fail_reflect += r ? 1 : 0;
            fail_shadow += sh ? 1 : 0;
            const auto k = static_cast<std::size_t>(s.stratum);
            n_stratum[k] += 2;
            fail_stratum[k] += (r ? 1 : 0) + (sh ? 1 : 0);
        }
        const std::size_t rays = 2 * starts.size();
        const double ns = rays ? sw.ns() / static_cast<double>(rays) : 0.0;
        std::string note = "reflection " + std::to_string(fail_reflect) + ", shadow " +
                           std::to_string(fail_shadow);
        if (stratified) {
            note += "; 1<=|c|/size<=1e4: " + std::to_string(fail_stratum[0]) + " of " +
                    std::to_string(n_stratum[0]) + ", beyond: " + std::to_string(fail_stratum[1]) +
                    " of " + std::to_string(n_stratum[1]);
        }
        if (policy == OffsetPolicy::epsilon) {
            note += "; epsilon " + std::to_string(default_offset_epsilon);
        }
        if (!extra_note.empty()) {
            note += "; " + extra_note;
        }
        const std::string subject = std::string(to_string(policy)) + " " + label;
        rows.push_back(make_row(case_name, subject, precision_of<T>(), rays,
                                fail_reflect + fail_shadow, "re-intersections", ns, note));
        if (stratified) {
            rows.push_back(make_row(
                case_name, subject + " 1<=|c|/size<=1e4", precision_of<T>(), n_stratum[0],
                fail_stratum[0], "re-intersections", ns,
                "the rows' stratum of shapes between 1e-4 |c| and |c| in size (c: centre)"));
        }
    }
}

/// log-uniform magnitude in [1e-8, 1e8].
double log_uniform(Sampler& rng) {
    return std::pow(10.0, rng.uniform(-8, 8));
}

/// Random shapes with their primary rays, strata (0: 1 <= |c| / size <= 1e4, c: the shape's
/// centre), shadow directions and lengths, and the count of shapes that rounding collapsed.
template <class T, class Shape>
struct RandomCases {
    std::vector<Shape> shapes;
    std::vector<Ray<T>> primaries;
    std::vector<int> strata;
    std::vector<Vec3d> shadow_dirs;
    std::vector<double> shadow_len;
    std::size_t degenerate = 0;
};

/// opt.rays random shapes from the stream: centre c = unit * |c| and size, both log-uniform in
/// [1e-8, 1e8]; make(rng, c, size) draws the shape (rounded to T) and its primary ray, or nothing
/// when rounding collapsed the shape. Shadow directions are uniform, lengths size * 10^[-1, 1].
template <class T, class Shape, class Make>
RandomCases<T, Shape> random_cases(const Options& opt, std::uint64_t stream, const Make& make) {
    Sampler rng(opt.seed, stream);
    RandomCases<T, Shape> k;
    while (k.shapes.size() < opt.rays) {
        const Vec3d c = rng.unit() * log_uniform(rng);
        const double size = log_uniform(rng);
        const std::optional<std::pair<Shape, Ray<T>>> made = make(rng, c, size);
        if (!made) {
            ++k.degenerate;
            continue;
        }
        k.shapes.push_back(made->first);
        k.primaries.push_back(made->second);
        k.strata.push_back(size <= length(c) && length(c) <= 1e4 * size ? 0 : 1);
        k.shadow_dirs.push_back(rng.unit());
        k.shadow_len.push_back(size * std::pow(10.0, rng.uniform(-1, 1)));
    }
    return k;
}

/// Rows per policy for method M over random cases (stratified). A start is the primary's hit:
/// frame(i, prepared shape, hit, start) sets its point and outside normal (false: no normal);
/// the reflected primary, and a shadow target along the case's shadow direction turned outside.
template <class T, class M, class Shape, class Frame>
void random_case_rows(const RandomCases<T, Shape>& k,
                      const Frame& frame,
                      const std::string& case_name,
                      const std::string& label,
                      const std::string& also_skipped,
                      std::vector<Row>& rows) {
    std::vector<typename M::Prepared> prep;
    for (const Shape& shape : k.shapes) {
        prep.push_back(M::prepare(shape));
    }
    const Starts<T> st =
        collect_starts<T>(k.shapes.size(), [&](std::size_t i) -> std::optional<Start<T>> {
            const auto hit = M::intersect(prep[i], k.primaries[i]);
            Start<T> s;
            s.shape = static_cast<std::uint32_t>(i);
            if (!hit || !frame(i, prep[i], *hit, s)) {
                return std::nullopt;
            }
            s.reflect = reflect(k.primaries[i].dir, s.n);
            const Vec3d sd = into_hemisphere(k.shadow_dirs[i], Vec3d(s.n));
            s.target = Vec3<T>(Vec3d(s.p) + sd * k.shadow_len[i]);
            s.stratum = k.strata[i];
            return s;
        });
    policy_rows<T>(st.starts, own_shape_hit<M>(prep), case_name, label,
                   skipped_note(st, also_skipped), true, rows);
}

/// Random triangles: vertices centre + unit * size, rounded to T; the primary ray comes from 3
/// sizes away towards a random interior point. Per triangle intersector M: rows per policy.
template <class T>
void triangle_rows(const Options& opt, std::vector<Row>& rows) {
    const auto k = random_cases<T, Triangle<T>>(
        opt, std::is_same_v<T, float> ? 500 : 600,
        [](Sampler& rng, const Vec3d& c,
           double size) -> std::optional<std::pair<Triangle<T>, Ray<T>>> {
            const Triangle<T> tri{Vec3<T>(c + rng.unit() * size), Vec3<T>(c + rng.unit() * size),
                                  Vec3<T>(c + rng.unit() * size)};
            if (is_degenerate(tri.p0, tri.p1, tri.p2)) {
                return std::nullopt;  // collapsed by rounding to T: no surface to leave
            }
            double b1 = rng.uniform(0, 1), b2 = rng.uniform(0, 1);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            const Vec3d p0(tri.p0), p1(tri.p1), p2(tri.p2);
            const Vec3d aim = p0 + (p1 - p0) * b1 + (p2 - p0) * b2;
            const Vec3d org = aim + rng.unit() * (3 * size);
            return std::pair{tri, Ray<T>{Vec3<T>(org), Vec3<T>(aim - org)}};
        });
    const std::string collapsed = std::to_string(k.degenerate) + " triangles collapsed by rounding";
    for_each_triangle_intersector<T>([&]<class M>() {
        for (const bool bary : {false, true}) {
            const auto frame = [&](std::size_t i, const auto&, const auto& hit, Start<T>& s) {
                const Triangle<T>& tri = k.shapes[i];
                const Ray<T>& primary = k.primaries[i];
                // The renderer's hit point o + t d (trace/surface.cpp), or the barycentric point
                // Wächter & Binder assume (its error is relative to the vertices, not the ray
                // length).
                s.p = bary ? tri.p0 * (T(1) - hit.u - hit.v) + tri.p1 * hit.u + tri.p2 * hit.v
                           : primary.at(hit.t);
                s.n = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
                if (dot(s.n, primary.dir) > T(0)) {
                    s.n = -s.n;
                }
                return true;
            };
            random_case_rows<T, M>(k, frame, "self_intersection/triangles",
                                   std::string(M::name) + (bary ? " p=barycentric" : " p=o+td"),
                                   collapsed, rows);
        }
    });
}

/// Random spheres: radius r = size, rounded to T; primary rays from 3 r away towards a point
/// within 0.9 r of the centre.
template <class T>
void sphere_rows(const Options& opt, std::vector<Row>& rows) {
    const auto k = random_cases<T, Sphere<T>>(
        opt, std::is_same_v<T, float> ? 510 : 610,
        [](Sampler& rng, const Vec3d& c, double r) -> std::optional<std::pair<Sphere<T>, Ray<T>>> {
            const Vec3d aim = c + rng.ball(0.9 * r);
            const Vec3d org = c + rng.unit() * (3 * r);
            return std::pair{Sphere<T>{Vec3<T>(c), static_cast<T>(r)},
                             Ray<T>{Vec3<T>(org), Vec3<T>(aim - org)}};
        });
    for_each_sphere_method<T>([&]<class M>() {
        const auto frame = [&](std::size_t i, const auto& prep, const auto& hit, Start<T>& s) {
            s.p = k.primaries[i].at(hit.t);
            s.n = sphere_normal(prep, s.p);
            return is_finite(s.n);  // false: hit point rounded onto the centre, no normal
        };
        random_case_rows<T, M>(k, frame, "self_intersection/spheres", std::string(M::name), {},
                               rows);
    });
}

/// Flake contact rows from sphere starts: hit points on a child within 30 degrees of its contact
/// with the parent (child on parent), and on the root within 30 degrees of its lowest point.
template <class T>
void flake_sphere_rows(const Options& opt,
                       const Scene& scene,
                       const std::vector<gen::FlakeSphere>& flake,
                       Sampler& rng,
                       const std::string& case_name,
                       std::vector<Row>& rows) {
    // Points on sphere `shape` near the unit direction `toward` (from its centre), within `cone`.
    const auto near_point = [&](const Vec3d& toward, double cone) {
        for (;;) {
            const Vec3d u = rng.unit();
            if (dot(u, toward) >= std::cos(cone)) {
                return u;
            }
        }
    };
    constexpr double cone = 30 * std::numbers::pi / 180;
    const std::size_t n = opt.rays;
    // Sphere starts: child on parent (children 1..) and the root's bottom.
    for (int kind = 0; kind < 2; ++kind) {
        std::vector<std::uint32_t> which;
        std::vector<Ray<T>> primaries;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t k =
                kind == 0 ? static_cast<std::uint32_t>(1 + rng.index(flake.size() - 1)) : 0;
            const Vec3d c(scene.spheres[k].center);
            const double r = static_cast<double>(scene.spheres[k].radius);
            const Vec3d toward = kind == 0 ? -flake[k].axis : Vec3d{0, 0, -1};
            const Vec3d u = near_point(toward, cone);
            const Vec3d target = c + u * r;
            const Vec3d from = target + hemisphere(rng, u) * (r * rng.uniform(0.05, 1));
            which.push_back(k);
            primaries.push_back({Vec3<T>(from), Vec3<T>(target - from)});
        }
        const std::string label = kind == 0 ? "child-on-parent" : "root-on-floor(root)";
        for_each_sphere_method<T>([&]<class M>() {
            std::vector<typename M::Prepared> prep;
            for (const SphereObject& s : scene.spheres) {
                prep.push_back(M::prepare(Sphere<T>{Vec3<T>(s.center), static_cast<T>(s.radius)}));
            }
            const Starts<T> st =
                collect_starts<T>(primaries.size(), [&](std::size_t i) -> std::optional<Start<T>> {
                    const auto hit = M::intersect(prep[which[i]], primaries[i]);
                    if (!hit) {
                        return std::nullopt;
                    }
                    Start<T> s;
                    s.shape = which[i];
                    s.p = primaries[i].at(hit->t);
                    s.n = sphere_normal(prep[which[i]], s.p);
                    s.reflect = reflect(primaries[i].dir, s.n);
                    const double r = static_cast<double>(scene.spheres[which[i]].radius);
                    s.target = Vec3<T>(Vec3d(s.p) + hemisphere(rng, Vec3d(s.n)) *
                                                        (r * std::pow(10.0, rng.uniform(-2, 0))));
                    return s;
                });
            policy_rows<T>(st.starts, own_shape_hit<M>(prep), case_name,
                           label + " " + std::string(M::name), skipped_note(st), false, rows);
        });
    }
}

/// Flake contact rows from floor starts: hit points on the floor within 0.05 of the root's
/// contact point (which lies on the diagonal shared by the floor's two triangles).
template <class T>
void flake_floor_rows(const Options& opt,
                      const Scene& scene,
                      Sampler& rng,
                      const std::string& case_name,
                      std::vector<Row>& rows) {
    const std::size_t n = opt.rays;
    // Floor starts: the polygon as the fan (0, 1, 2), (0, 2, 3); primaries from above.
    const std::vector<Vec3f>& q = scene.polygons[0].vertices;
    const std::array<Triangle<T>, 2> floor{
        Triangle<T>{Vec3<T>(q[0]), Vec3<T>(q[1]), Vec3<T>(q[2])},
        Triangle<T>{Vec3<T>(q[0]), Vec3<T>(q[2]), Vec3<T>(q[3])}};
    const Vec3d contact(scene.spheres[0].center - Vec3f{0, 0, scene.spheres[0].radius});
    std::vector<Ray<T>> primaries;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d d = rng.ball(0.05);
        const Vec3d target = contact + Vec3d{d.x, d.y, 0};
        const Vec3d from = target + hemisphere(rng, Vec3d{0, 0, 1}) * rng.uniform(0.01, 1);
        primaries.push_back({Vec3<T>(from), Vec3<T>(target - from)});
    }
    for_each_triangle_intersector<T>([&]<class M>() {
        const std::array<typename M::Prepared, 2> prep{M::prepare(floor[0]), M::prepare(floor[1])};
        const Starts<T> st =
            collect_starts<T>(primaries.size(), [&](std::size_t i) -> std::optional<Start<T>> {
                const Ray<T>& ray = primaries[i];
                Ray<T> r = ray;
                std::optional<PrimHit<T>> best;
                for (const auto& p : prep) {
                    if (const auto h = M::intersect(p, r)) {
                        best = h;
                        r.tmax = h->t;
                    }
                }
                if (!best) {
                    return std::nullopt;
                }
                Start<T> s;
                s.p = ray.at(best->t);
                s.n = {T(0), T(0), T(1)};
                s.reflect = {ray.dir.x, ray.dir.y, -ray.dir.z};
                s.target = Vec3<T>(Vec3d(s.p) + hemisphere(rng, Vec3d{0, 0, 1}) *
                                                    std::pow(10.0, rng.uniform(-3, 0)));
                return s;
            });
        const auto self_hit = [&](std::uint32_t, const Ray<T>& ray) {
            return M::occluded(prep[0], ray) || M::occluded(prep[1], ray);
        };
        policy_rows<T>(st.starts, self_hit, case_name,
                       "root-on-floor(floor) " + std::string(M::name), skipped_note(st), false,
                       rows);
    });
}

/// The flake's tangent contacts (size factor 2: 91 spheres on the floor polygon). Child on
/// parent: hit points on each child within 30 degrees of its contact with the parent. Root on
/// floor: hit points on the root within 30 degrees of its lowest point, and on the floor within
/// 0.05 of the contact point (which lies on the diagonal shared by the floor's two triangles).
/// Only the surface a ray leaves counts as a re-intersection.
template <class T>
void flake_rows(const Options& opt, std::vector<Row>& rows) {
    gen::GenOptions go;
    go.size = 2;
    const Scene scene = gen::generate("flake", go);
    const std::vector<gen::FlakeSphere> flake = gen::sphere_flake(go.size);
    if (scene.spheres.size() != flake.size() || scene.polygons.size() != 1) {
        rows.push_back(make_row("self_intersection/flake_contacts", "setup", "-", 0, 1,
                                "setup errors", 0, "flake scene layout changed"));
        return;
    }
    const std::string case_name = "self_intersection/flake_contacts";
    Sampler rng(opt.seed, std::is_same_v<T, float> ? 520 : 620);
    flake_sphere_rows<T>(opt, scene, flake, rng, case_name, rows);
    flake_floor_rows<T>(opt, scene, rng, case_name, rows);
}

}  // namespace

std::vector<Row> run_self_intersection(const Options& opt) {
    std::vector<Row> rows;
    triangle_rows<float>(opt, rows);
    triangle_rows<double>(opt, rows);
    sphere_rows<float>(opt, rows);
    sphere_rows<double>(opt, rows);
    flake_rows<float>(opt, rows);
    flake_rows<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
