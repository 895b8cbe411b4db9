// Normals per primitive type: triangle and polygon (geometric), sphere (radial), boxes (the face
// whose slab the point is deepest in), implicit (normalised gradient).
#include "trace/surface.h"

#include "intersect/implicit/tangle_cube.h"
#include "intersect/implicit/torus.h"
#include "intersect/polygon/polygon.h"

#include <cmath>

namespace rtlab {

namespace {

// Normal of the box face nearest to p: the axis where p is relatively furthest from the centre.
Vec3f box_normal(const Vec3f& local, const Vec3f& half) {
    std::size_t best = 0;
    float best_v = -1;
    for (std::size_t a = 0; a < 3; ++a) {
        const float v = half[a] > 0 ? std::abs(local[a]) / half[a] : std::abs(local[a]);
        if (v > best_v) {
            best_v = v;
            best = a;
        }
    }
    Vec3f n{0, 0, 0};
    n[best] = local[best] < 0 ? -1.0f : 1.0f;
    return n;
}

}  // namespace

SurfacePoint surface_at(const Scene& scene,
                        const std::vector<std::uint32_t>& base,
                        const Hit& hit,
                        const Rayf& ray) {
    SurfacePoint sp;
    sp.p = ray.at(hit.t);
    const PrimitiveLocation loc = locate_primitive(base, hit.prim);
    const ObjectRef r = scene.order[loc.object];
    Vec3f n{0, 0, 1};
    switch (r.type) {
    case PrimType::mesh: {
        const MeshObject& m = scene.meshes[r.index];
        const auto& f = m.mesh.triangles[loc.local];
        const Vec3f& a = m.mesh.positions[f[0]];
        n = cross(m.mesh.positions[f[1]] - a, m.mesh.positions[f[2]] - a);
        sp.material = m.material;
        break;
    }
    case PrimType::sphere: {
        const SphereObject& s = scene.spheres[r.index];
        n = sp.p - s.center;
        sp.material = s.material;
        break;
    }
    case PrimType::polygon: {
        const PolygonObject& pg = scene.polygons[r.index];
        n = detail::newell_normal(pg.vertices);
        sp.material = pg.material;
        break;
    }
    case PrimType::box: {
        const BoxObject& b = scene.boxes[r.index];
        n = box_normal(sp.p - b.bounds.center(), b.bounds.diagonal() * 0.5f);
        sp.material = b.material;
        break;
    }
    case PrimType::obb: {
        const ObbObject& o = scene.obbs[r.index];
        const Vec3f d = sp.p - o.center;
        const Vec3f local{dot(d, o.axes[0]), dot(d, o.axes[1]), dot(d, o.axes[2])};
        const Vec3f ln = box_normal(local, o.half);
        n = o.axes[0] * ln.x + o.axes[1] * ln.y + o.axes[2] * ln.z;
        sp.material = o.material;
        break;
    }
    case PrimType::implicit: {
        const ImplicitObject& o = scene.implicits[r.index];
        n = o.kind == ImplicitKind::torus ? Torus<float>{o.center, o.major, o.minor}.gradient(sp.p)
                                          : TangleCube<float>{o.center, o.scale}.gradient(sp.p);
        sp.material = o.material;
        break;
    }
    }
    const float len = length(n);
    n = len > 0 && std::isfinite(len) ? n / len : Vec3f{0, 0, 1};
    sp.front_face = dot(n, ray.dir) <= 0;
    sp.n = sp.front_face ? n : -n;
    return sp;
}

}  // namespace rtlab
