// The second phase of a hit: the object's table entry (scene/prim_*.h) gives the unnormalised
// normal; here it is normalised and turned to face the ray.
#include "trace/surface.h"

#include <cmath>

namespace rtlab {

SurfacePoint surface_at(const Scene& scene,
                        const std::vector<std::uint32_t>& base,
                        const Hit& hit,
                        const Rayf& ray) {
    SurfacePoint sp;
    sp.p = ray.at(hit.t);
    const PrimitiveLocation loc = locate_primitive(base, hit.prim);
    const ObjectRef r = scene.order[loc.object];
    Vec3f n = visit_object(scene, r, [&]<class P>(const auto& o) {
        sp.material = o.material;
        return P::normal(o, loc.local, sp.p);
    });
    const float len = length(n);
    n = len > 0 && std::isfinite(len) ? n / len : Vec3f{0, 0, 1};
    sp.front_face = dot(n, ray.dir) <= 0;
    sp.n = sp.front_face ? n : -n;
    return sp;
}

}  // namespace rtlab
