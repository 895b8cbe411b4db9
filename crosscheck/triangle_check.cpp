// Triangle cross-check: every triangle method, in float and double (and the certified test of exact
// mode, "exact", in float), finds the closest hit of each ray over a closed, vertex-perturbed
// sphere mesh by brute force; CGAL's exact kernel (Epeck, with an AABB tree) gives the exact
// closest hit of the same ray. Rays are generated in float so both
// precisions trace the identical ray.
#include "base/sampler.h"
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/ray_sets.h"
#include "intersect/triangle/methods.h"
#include "intersect/triangle/sphere_mesh.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <utility>
#include <vector>

namespace rtlab::xcheck {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalTriangles = std::vector<K::Triangle_3>;
using CgalPrimitive = CGAL::AABB_triangle_primitive<K, CgalTriangles::const_iterator>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CgalPrimitive>>;

/// One named ray set; rays are float so the double run traces the same ray exactly.
struct RaySet {
    std::string name;
    std::vector<Rayf> rays;
};

/// A mesh-level answer: whether the ray hits any triangle, and the closest t.
struct Answer {
    bool hit = false;
    double t = 0;
};

Vec3f to_float(const Vec3d& v) {
    return Vec3f(v);
}

/// For each face and each edge (f[e], f[e + 1]), the face across that edge.
std::vector<std::array<std::uint32_t, 3>> face_neighbours(const IndexedMesh& mesh) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> by_edge;
    for (std::uint32_t i = 0; i < mesh.faces.size(); ++i) {
        for (std::size_t e = 0; e < 3; ++e) {
            by_edge[{mesh.faces[i][e], mesh.faces[i][(e + 1) % 3]}] = i;
        }
    }
    std::vector<std::array<std::uint32_t, 3>> out(mesh.faces.size());
    for (std::uint32_t i = 0; i < mesh.faces.size(); ++i) {
        for (std::size_t e = 0; e < 3; ++e) {
            // The mesh is closed and consistently wound: the neighbour has the edge reversed.
            out[i][e] = by_edge.at({mesh.faces[i][(e + 1) % 3], mesh.faces[i][e]});
        }
    }
    return out;
}

/// Cosine between d and the normal of face i (in double).
double facing(const IndexedMesh& mesh, std::uint32_t i, const Vec3d& d) {
    const Triangled t = mesh.triangle<double>(i);
    return dot(normalize(cross(t.p1 - t.p0, t.p2 - t.p0)), normalize(d));
}

/// A ray at a random point of a shared edge (rounded to float). The ray must cross the surface
/// there: both faces of the edge see it from the same side at an angle (cosine beyond 0.05), so
/// it is never tangent to the mesh and the exact answer is a transversal hit near the edge.
Rayf edge_ray(const IndexedMesh& mesh,
              const std::vector<std::array<std::uint32_t, 3>>& neighbours,
              Sampler& rng,
              bool from_inside) {
    for (;;) {
        const std::uint32_t f = static_cast<std::uint32_t>(rng.index(mesh.faces.size()));
        const std::size_t e = rng.index(3);
        const Vec3f a = mesh.vertices[mesh.faces[f][e]];
        const Vec3f b = mesh.vertices[mesh.faces[f][(e + 1) % 3]];
        const Vec3f target = a + (b - a) * static_cast<float>(rng.uniform(0, 1));
        Rayf r;
        r.org = to_float(from_inside ? rng.ball(0.5) : rng.unit() * 3.0);
        r.dir = target - r.org;
        const double c0 = facing(mesh, f, Vec3d(r.dir));
        const double c1 = facing(mesh, neighbours[f][e], Vec3d(r.dir));
        if ((c0 > 0.05 && c1 > 0.05) || (c0 < -0.05 && c1 < -0.05)) {
            return r;
        }
    }
}

/// The six ray sets, opt.rays split evenly among them. Mesh radius is in [0.9, 1.1].
std::vector<RaySet> make_ray_sets(const IndexedMesh& mesh, std::size_t total, std::uint64_t seed) {
    const auto neighbours = face_neighbours(mesh);
    const char* names[] = {"inside", "vertex", "edge", "grazing", "axis", "outside"};
    constexpr std::size_t n_sets = 6;
    std::vector<RaySet> sets;
    for (std::size_t s = 0; s < n_sets; ++s) {
        Sampler rng(seed, s);
        RaySet set{names[s], {}};
        const std::size_t n = total / n_sets + (s < total % n_sets ? 1 : 0);
        for (std::size_t i = 0; i < n; ++i) {
            Rayf r;
            switch (s) {
            case 0:  // random rays from inside: every one must hit
                r.org = to_float(rng.ball(0.5));
                r.dir = to_float(rng.unit());
                break;
            case 1: {  // from the centre exactly at a vertex; power-of-two scale keeps it exact
                const Vec3f v = mesh.vertices[i % mesh.vertices.size()];
                const int k = static_cast<int>((i / mesh.vertices.size()) % 5) - 2;
                r.org = Vec3f{0, 0, 0};
                r.dir = v * std::ldexp(1.0f, k);
                break;
            }
            case 2: {  // at a point on a shared edge, from inside or outside; see edge_ray
                r = edge_ray(mesh, neighbours, rng, i % 2 == 0);
                break;
            }
            case 3: {  // from outside, parallel to d, offset near the silhouette radius
                const Vec3d d = rng.unit();
                const Vec3d helper = std::abs(d.x) < 0.5 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
                const Vec3d e1 = normalize(cross(d, helper));
                const Vec3d e2 = cross(d, e1);
                const double rho = rng.uniform(0.85, 1.12);
                const double phi = rng.uniform(0, 2 * std::numbers::pi);
                r.org = to_float(d * -3.0 + (e1 * std::cos(phi) + e2 * std::sin(phi)) * rho);
                r.dir = to_float(d);
                break;
            }
            case 4: {  // one or two zero direction components, from inside or outside
                const std::size_t axis = rng.index(3);
                Vec3d d;
                d[axis] = rng.uniform(0, 1) < 0.5 ? -1.0 : 1.0;
                if (i % 2 == 0) {
                    d[(axis + 1) % 3] = rng.uniform(-1, 1);
                }
                d = d * rng.uniform(0.5, 2.0);
                const Vec3f df = to_float(d);
                if (i % 4 < 2) {
                    r.org = to_float(rng.ball(0.5));
                } else {
                    r.org = to_float(rng.ball(1.2) - normalize(Vec3d(df)) * 3.0);
                }
                r.dir = df;
                break;
            }
            default: {  // random from outside; some miss
                r.org = to_float(rng.unit() * rng.uniform(2, 4));
                r.dir = to_float(rng.ball(1.5)) - r.org;
                break;
            }
            }
            set.rays.push_back(r);
        }
        sets.push_back(std::move(set));
    }
    return sets;
}

/// Exact closest hit of one ray: t along the dominant direction axis of the exact point.
Answer exact_closest(const CgalTree& tree, const Rayf& rf) {
    const K::Point_3 org(rf.org.x, rf.org.y, rf.org.z);
    const K::Vector_3 dir(rf.dir.x, rf.dir.y, rf.dir.z);
    const K::Ray_3 ray(org, dir);
    const std::size_t k = max_abs_axis(rf.dir);
    std::vector<CgalTree::Primitive_id> ids;
    tree.all_intersected_primitives(ray, std::back_inserter(ids));
    std::optional<K::FT> best;
    const auto consider = [&](const K::Point_3& p) {
        const K::FT t =
            (p[static_cast<int>(k)] - org[static_cast<int>(k)]) / dir[static_cast<int>(k)];
        if (!best || t < *best) {
            best = t;
        }
    };
    for (const CgalTree::Primitive_id& id : ids) {
        const auto res = CGAL::intersection(ray, *id);
        if (!res) {
            continue;
        }
        if (const K::Point_3* p = boost::get<K::Point_3>(&*res)) {
            consider(*p);
        } else if (const K::Segment_3* s = boost::get<K::Segment_3>(&*res)) {
            consider(s->source());
            consider(s->target());
        }
    }
    return best ? Answer{true, CGAL::to_double(*best)} : Answer{};
}

/// The exact answers for all rays, in parallel; each task builds its own tree so no lazy exact
/// object is shared between threads.
std::vector<Answer> exact_answers(const IndexedMesh& mesh, const std::vector<Rayf>& rays) {
    std::vector<Answer> out(rays.size());
    const std::size_t grain = std::max<std::size_t>(512, rays.size() / 32);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), grain),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          CgalTriangles tris;
                          for (const auto& f : mesh.faces) {
                              const auto pt = [&](std::uint32_t i) {
                                  const Vec3f v = mesh.vertices[i];
                                  return K::Point_3(v.x, v.y, v.z);
                              };
                              tris.emplace_back(pt(f[0]), pt(f[1]), pt(f[2]));
                          }
                          const CgalTree tree(tris.begin(), tris.end());
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              out[i] = exact_closest(tree, rays[i]);
                          }
                      });
    return out;
}

/// One method in one precision over every set: brute-force closest hit (any hit for
/// occlusion-only methods) with the ray's set-up done once per ray, timed single-threaded (the
/// set-up pass and the test pass apart), compared with the exact answers.
template <class M>
void run_method(const IndexedMesh& mesh,
                const std::vector<RaySet>& sets,
                const std::vector<std::vector<Answer>>& exact,
                const Options& opt,
                std::vector<Row>& rows) {
    using T = typename M::Scalar;
    constexpr bool has_t = IntersectionMethod<M>;
    std::vector<typename M::Prepared> prims;
    prims.reserve(mesh.faces.size());
    for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        prims.push_back(M::prepare(mesh.triangle<T>(i)));
    }
    MethodRows out("triangle", std::string(M::name), precision_name<T>(), t_tolerance<T>(),
                   opt.by_set, has_t);
    for (std::size_t s = 0; s < sets.size(); ++s) {
        std::vector<Ray<T>> rays;
        for (const Rayf& r : sets[s].rays) {
            rays.push_back(static_cast<Ray<T>>(r));
        }
        SetupTiming setup;
        const std::vector<RayDataOf<M>> data = precompute_all<M>(rays, setup);
        std::vector<Answer> answers(rays.size());
        std::size_t tests = 0;
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < answers.size(); ++i) {
            Ray<T> ray = rays[i];  // closest hit shrinks tmax; the set-up data stays valid
            Answer a;
            for (const auto& p : prims) {
                ++tests;
                if constexpr (has_t) {
                    if (const auto h = intersect_with<M>(p, ray, data[i])) {
                        a = {true, static_cast<double>(h->t)};
                        ray.tmax = h->t;
                    }
                } else if (occluded_with<M>(p, ray, data[i])) {
                    a.hit = true;
                    break;
                }
            }
            answers[i] = a;
        }
        const double ns =
            std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start)
                .count();
        Accumulator acc(t_tolerance<T>(), has_t);
        for (std::size_t i = 0; i < answers.size(); ++i) {
            acc.add(answers[i].hit, exact[s][i].hit, answers[i].t, exact[s][i].t);
        }
        out.add_set(acc, sets[s].name, ns, tests, setup);
    }
    out.emit(rows);
}

}  // namespace

std::vector<std::string> triangle_methods() {
    return method_names(for_each_checked_triangle);
}

std::vector<Row> check_triangles(const Options& opt) {
    const std::vector<std::string> methods =
        select_methods(triangle_methods(), opt.methods, "triangle");
    const IndexedMesh mesh = perturbed_sphere_mesh(opt.seed);
    const std::vector<RaySet> sets = make_ray_sets(mesh, opt.rays, opt.seed);
    std::vector<std::vector<Answer>> exact;
    for (const RaySet& s : sets) {
        exact.push_back(exact_answers(mesh, s.rays));
    }
    std::vector<Row> rows;
    run_wanted(methods, opt, for_each_checked_triangle,
               [&]<class M>() { run_method<M>(mesh, sets, exact, opt, rows); });
    return rows;
}

BenchCases<Triangle<float>> triangle_bench_cases(std::size_t n, std::uint64_t seed) {
    const IndexedMesh mesh = perturbed_sphere_mesh(seed);
    BenchCases<Triangle<float>> out;
    out.closest_of_all = true;
    for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        out.shapes.push_back(mesh.triangle<float>(i));
    }
    // The check's sets "outside", "edge" and "grazing" (n rays each), then far rays from 1e3 to
    // 1e4 mesh radii away aimed into the ball of radius 1.2.
    const std::vector<RaySet> sets = make_ray_sets(mesh, 6 * n, seed);
    const auto find = [&](std::string_view name) -> const std::vector<Rayf>& {
        for (const RaySet& s : sets) {
            if (s.name == name) {
                return s.rays;
            }
        }
        return sets.back().rays;
    };
    std::vector<Rayf> far;
    Sampler rng(seed, 100);  // a stream of its own, apart from the six sets' 0 to 5
    for (std::size_t i = 0; i < n; ++i) {
        Rayf r;
        r.org = to_float(rng.unit() * rng.uniform(1e3, 1e4));
        r.dir = to_float(rng.ball(1.2)) - r.org;
        far.push_back(r);
    }
    const std::array<const std::vector<Rayf>*, 4> by_set{&find("outside"), &find("edge"),
                                                         &find("grazing"), &far};
    for (std::size_t s = 0; s < by_set.size(); ++s) {
        const std::vector<Answer> exact = exact_answers(mesh, *by_set[s]);
        for (std::size_t i = 0; i < exact.size(); ++i) {
            Sample smp;
            smp.ray = (*by_set[s])[i];
            smp.set = static_cast<std::uint8_t>(s);
            out.samples.push_back(smp);
            out.truth.push_back({exact[i].hit, exact[i].t});
        }
    }
    return out;
}

}  // namespace rtlab::xcheck
