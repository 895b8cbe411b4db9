// Adversarial leak rays, generated rather than hand-picked: closed UV spheres whose vertex radii
// are strongly jittered (several jitters, resolutions and seeds), traced from points of each
// mesh's kernel towards its vertices and shared-edge points, towards points on the built
// structure's own planes (kd split planes, grid cell boundaries, BVH box faces: inside a face, on
// its edges, at its corners), and lying within rounding of those planes, nearly or exactly
// parallel to them, and from far outside into the kernel. Every ray starts inside a closed mesh or
// enters it, so every ray must hit.
#include "intersect/triangle/sphere_mesh.h"
#include "stability/case_util.h"
#include "stability/cases.h"
#include "stability/fixtures.h"
#include "stability/structure_planes.h"

#include <array>
#include <cmath>
#include <variant>

namespace rtlab::stab {

namespace {

/// One mesh of the case: a UV sphere of `rings` x `segments` with vertex radii 1 +- jitter.
struct JitteredSphere {
    double jitter;
    std::uint32_t rings, segments;
};

// Mild to strong jitter, coarse to fine: steep, thin triangles meet at vertices whose
// coordinates the builders take as split planes and box faces.
constexpr JitteredSphere adversarial_meshes[] = {{0.1, 16, 24}, {0.2, 8, 12},   {0.3, 12, 16},
                                                 {0.45, 8, 12}, {0.45, 24, 32}, {0.3, 32, 48}};

/// The kernel of a closed mesh that is star-shaped around the origin: the points on the inner
/// side of every face's plane, from which every ray meets the mesh.
class Kernel {
public:
    explicit Kernel(const TriangleMesh& mesh) {
        for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
            const auto c = mesh.corners(i);
            const Vec3d a(c[0]), b(c[1]), d(c[2]);
            Vec3d n = cross(b - a, d - a);
            n = n / length(n);
            double off = dot(n, a);
            if (off < 0) {  // orient so the origin lies on the inner (negative) side
                n = -n;
                off = -off;
            }
            faces_.push_back({n, off});
            inradius_ = std::min(inradius_, off);
        }
    }
    /// Distance from the origin to the nearest face plane: the ball of this radius is inside.
    double inradius() const { return inradius_; }
    /// True when p lies in the kernel at least `margin` from every face plane.
    bool contains(const Vec3d& p, double margin = 1e-6) const {
        for (const auto& [n, off] : faces_) {
            if (dot(n, p) > off - margin) {
                return false;
            }
        }
        return true;
    }

private:
    std::vector<std::pair<Vec3d, double>> faces_;
    double inradius_ = std::numeric_limits<double>::infinity();
};

/// Generates the rays for one mesh and one built structure.
class RayMaker {
public:
    RayMaker(const TriangleMesh& mesh, std::vector<StructurePlane> planes, std::uint64_t seed)
        : mesh_(mesh), kernel_(mesh), planes_(std::move(planes)), rng_(seed, 303) {
        // Planes that cross the kernel's inscribed ball can carry ray origins.
        for (std::size_t i = 0; i < planes_.size(); ++i) {
            if (std::abs(static_cast<double>(planes_[i].pos)) < 0.9 * kernel_.inradius()) {
                through_kernel_.push_back(i);
            }
        }
    }

    /// Ray i of the set (eight kinds in turn; a quarter through vertices from the exact centre).
    Rayf ray(std::size_t i) {
        Rayf r;
        switch (i % 8) {
        case 0:
        case 7: {  // from the exact centre through a vertex: a scale by 2^k is exact
            const Vec3f v = mesh_.positions[rng_.index(mesh_.positions.size())];
            r.dir = v * std::ldexp(1.0f, static_cast<int>(rng_.index(5)) - 2);
            break;
        }
        case 1:  // from a kernel point at a vertex
            r.org = kernel_point();
            r.dir = mesh_.positions[rng_.index(mesh_.positions.size())] - r.org;
            break;
        case 2: {  // at a float point of a shared edge
            const auto& f = mesh_.triangles[rng_.index(mesh_.triangles.size())];
            const std::size_t e = rng_.index(3);
            const Vec3f a = mesh_.positions[f[e]], b = mesh_.positions[f[(e + 1) % 3]];
            r.org = rng_.index(2) == 0 ? Vec3f{} : kernel_point();
            r.dir = a + (b - a) * static_cast<float>(rng_.uniform(0, 1)) - r.org;
            break;
        }
        case 3:
        case 4:  // at a point of one of the structure's planes
            r.org = rng_.index(2) == 0 ? Vec3f{} : kernel_point();
            r.dir = plane_point() - r.org;
            break;
        case 5:  // from far outside (10 to 1e4 radii) into the kernel: rounding grows with |org|
            far(r);
            break;
        default:  // (6) within rounding of a plane, nearly or exactly parallel to it
            if (through_kernel_.empty()) {
                r.org = kernel_point();
                r.dir = plane_point() - r.org;
            } else {
                grazing(r);
            }
            break;
        }
        if (!is_valid(r)) {  // a target that rounded onto the origin
            r.dir = Vec3f(rng_.unit());
        }
        return r;
    }

private:
    /// A point of the kernel (rejection from a ball slightly larger than the inscribed one).
    Vec3f kernel_point() {
        for (;;) {
            const Vec3d p = rng_.ball(1.5 * kernel_.inradius());
            if (kernel_.contains(p)) {
                return Vec3f(p);
            }
        }
    }

    /// A float point of a random plane: inside its face, on an edge of it, or at a corner.
    Vec3f plane_point() {
        if (planes_.empty()) {
            return kernel_point() * 4.0f;
        }
        const StructurePlane& p = planes_[rng_.index(planes_.size())];
        Vec3f q;
        const std::size_t mode = rng_.index(3);  // 0 interior, 1 edge, 2 corner
        for (std::uint32_t a = 0; a < 3; ++a) {
            const float lo = p.face.lo[a], hi = p.face.hi[a];
            const bool snap = mode == 2 || (mode == 1 && a == (p.axis + 1 + rng_.index(2)) % 3);
            q[a] = snap ? (rng_.index(2) == 0 ? lo : hi)
                        : lo + (hi - lo) * static_cast<float>(rng_.uniform(0, 1));
        }
        q[p.axis] = p.pos;
        return q;
    }

    /// A ray from 10 to 1e4 radii away, aimed at a kernel point (half the time one on a plane
    /// through the kernel), far enough inside that the rounded direction still passes through the
    /// kernel: it enters the closed mesh, so it must hit. (Not at vertices: from outside, the
    /// exact ray may touch a vertex without entering.)
    void far(Rayf& r) {
        r.org = Vec3f(rng_.unit() * std::pow(10.0, rng_.uniform(1, 4)));
        // dir = target - org rounds by a few ulps of |org|; keep that far from the kernel's faces.
        const double margin = 8.0 * static_cast<double>(length(r.org)) * 0x1.0p-24;
        for (;;) {
            Vec3f target = kernel_point();
            if (!through_kernel_.empty() && rng_.index(2) == 0) {
                const StructurePlane& p =
                    planes_[through_kernel_[rng_.index(through_kernel_.size())]];
                target[p.axis] = p.pos;
            }
            if (kernel_.contains(Vec3d(target), margin)) {
                r.dir = target - r.org;
                return;
            }
        }
    }

    /// A ray starting on (or one float step beside) a plane through the kernel, whose direction
    /// is 10^-u (u in [1, 9]) or exactly 0 along the plane's normal.
    void grazing(Rayf& r) {
        const StructurePlane& p = planes_[through_kernel_[rng_.index(through_kernel_.size())]];
        for (;;) {
            r.org = kernel_point();
            r.org[p.axis] = p.pos;
            const std::size_t nudge = rng_.index(3);
            if (nudge != 0) {
                r.org[p.axis] = std::nextafter(p.pos, nudge == 1 ? -INFINITY : INFINITY);
            }
            if (kernel_.contains(Vec3d(r.org))) {
                break;
            }
        }
        Vec3d d = rng_.unit();
        d[p.axis] = rng_.index(8) == 0
                        ? 0.0
                        : (rng_.index(2) == 0 ? 1.0 : -1.0) * std::pow(10.0, -rng_.uniform(1, 9));
        r.dir = Vec3f(d);
    }

    const TriangleMesh& mesh_;
    Kernel kernel_;
    std::vector<StructurePlane> planes_;
    std::vector<std::size_t> through_kernel_;
    Sampler rng_;
};

}  // namespace

const AnyAccel& triangle_accel(const SceneTracer& tracer) {
    return std::visit([](const auto& set) -> const AnyAccel& { return set.accel; },
                      tracer.sets().at(0));
}

std::vector<Scene> adversarial_scenes(std::uint64_t seed) {
    std::vector<Scene> scenes;
    for (std::size_t k = 0; k < std::size(adversarial_meshes); ++k) {
        const JitteredSphere& m = adversarial_meshes[k];
        const IndexedMesh im = perturbed_sphere_mesh(seed * 16 + k, m.rings, m.segments, m.jitter);
        TriangleMesh mesh;
        mesh.positions = im.vertices;
        mesh.triangles = im.faces;
        scenes.push_back(mesh_scene(std::move(mesh)));
    }
    return scenes;
}

std::vector<Rayf> adversarial_rays(const TriangleMesh& mesh,
                                   const AnyAccel& accel,
                                   std::size_t count,
                                   std::uint64_t seed) {
    RayMaker maker(mesh, structure_planes(accel), seed);
    std::vector<Rayf> rays(count);
    for (std::size_t i = 0; i < count; ++i) {
        rays[i] = maker.ray(i);
    }
    return rays;
}

std::vector<Row> run_adversarial(const Options& opt) {
    return run_adversarial(opt, Selection{});
}

std::vector<Row> run_adversarial(const Options& opt, const Selection& sel) {
    const std::vector<Scene> scenes = adversarial_scenes(opt.seed);
    const std::size_t n = scenes.size();
    return leak_rows(
        "adversarial", scenes,
        [&](std::size_t k, const SceneTracer& tracer) {
            const std::size_t count = opt.rays * (k + 1) / n - opt.rays * k / n;
            return adversarial_rays(scenes[k].meshes[0].mesh, triangle_accel(tracer), count,
                                    opt.seed * 16 + k);
        },
        sel);
}

}  // namespace rtlab::stab
