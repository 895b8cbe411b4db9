// A tiny outside project: links rtlab::intersect from an installed rtlab and traces one ray.
#include "intersect/triangle/moller_trumbore.h"

#include <cstdio>

int main() {
    using M = rtlab::MollerTrumbore<float>;
    const auto tri = M::prepare({{-1, -1, 2}, {1, -1, 2}, {0, 1, 2}});
    const rtlab::Rayf ray{{0, 0, 0}, {0, 0, 1}};
    const auto hit = M::intersect(tri, ray);
    std::printf("t = %g\n", hit ? static_cast<double>(hit->t) : -1.0);
    return hit && hit->t == 2.0f ? 0 : 1;
}
