// Generator rows for the SPD databases: the NFF document through nff::to_scene (lights get the
// 1/sqrt(n) intensity rule); --as mesh flattens everything into one mesh.
#include "datasets_gen/scene_parts.h"
#include "datasets_gen/spd_databases.h"

#include <array>

namespace rtlab::gen {

namespace {

struct SpdText {
    std::string_view description;
    std::string_view formula;
};

// Descriptions by database, in spd::databases() order.
constexpr std::array<SpdText, 11> spd_text{{
    {"SPD balls: the sphere flake (9 children of 1/3 radius per sphere) on a floor, 3 lights",
     "spheres = (9^(SF+1)-1)/8 (SF 4: 7381) + 1 floor polygon"},
    {"SPD gears: SF^3 gears of 36 teeth (concave 144-gon faces, side quads) on a mirror ground",
     "polygons = 146*SF^3 + 1 (2 faces of 144 vertices per gear), 5 lights"},
    {"SPD jacks: crossed cylinders with end spheres, a half-size copy per octant",
     "per level k < SF: 8^k jacks of 6 spheres + 3 cylinders"},
    {"SPD lattice: (SF+1)^3 shiny spheres joined by matte cylinders, 6 lights",
     "spheres = (SF+1)^3, cylinders = 3*SF*(SF+1)^2"},
    {"SPD mount: Carpenter's fractal mountain (the SPD's hashed Gaussian displacement) and 4 "
     "glass spheres",
     "triangles = 2*4^SF (SF 6: 8192) + 4 spheres, 1 light"},
    {"SPD rings: a pyramid of 6-ring objects (cylinders and spheres), a wall",
     "spheres = cylinders = 5*SF*(SF+1)*(2*SF+1) + 1 wall polygon, 3 lights"},
    {"SPD shells: Pickover's seashell, overlapping spheres on a logarithmic spiral",
     "spheres = 180*2^SF/3 - (-180*2^SF*2/3) + 1 (SF 1: 361)"},
    {"SPD sombrero: a damped cosine height field, two triangles per grid cell",
     "triangles = 2*(32*2^(SF-1)-1)^2 (SF 1: 1922)"},
    {"SPD teapot: Newell's teapot, 32 Bezier patches in SF x SF cells of 2 triangles with vertex "
     "normals, on a checkerboard",
     "patches = 64*SF^2 minus the cusp triangles (SF 1: 56, SF 2: 240) + SF^2 squares"},
    {"SPD tetra: Sierpinski tetrahedron of SF-1 levels, 4 triangles per leaf",
     "triangles = 4^SF (SF 6: 4096)"},
    {"SPD tree: Aono & Kunii's tree of cones with spheres on the tips, a field",
     "spheres = cones = 2^(SF+1)-1 + 1 floor polygon, 7 lights"},
}};

GenCounts to_gen_counts(const nff::Counts& n, const GenOptions& o, std::size_t polygon_vertices) {
    GenCounts c = sphere_counts(n.spheres, o);
    c.cones = n.cones;
    if (o.as_mesh) {
        // Open NFF cones: tess.u triangle pairs around (append_cone); polygons: one fan
        // triangle per vertex.
        c.cones = 0;
        c.triangles =
            saturating_add(c.triangles, saturating_mul(n.cones, 2 * std::uint64_t(o.tess.u)));
        c.triangles = saturating_add(c.triangles, polygon_vertices);
    } else {
        c.polygons = n.polygons + n.patches;
        c.polygon_vertices = polygon_vertices;
    }
    return c;
}

template <std::size_t I>
GenCounts spd_counts(const GenOptions& o) {
    const spd::Database& d = spd::databases()[I];
    const nff::Counts n = d.counts(o.size);
    const std::size_t verts = n.vertices;
    return to_gen_counts(n, o, verts);
}

template <std::size_t I>
Scene spd_make(const GenOptions& o) {
    const spd::Database& d = spd::databases()[I];
    Scene s = nff::to_scene(d.document(o.size), d.name);
    if (o.as_mesh) {
        return scene_as_mesh(s, o);
    }
    return s;
}

template <std::size_t I>
Generator spd_row() {
    const spd::Database& d = spd::databases()[I];
    return {d.name,     spd_text[I].description, spd_text[I].formula, d.min_size, d.default_size,
            d.max_size, spd_counts<I>,           spd_make<I>};
}

}  // namespace

std::vector<Generator> spd_generators() {
    static_assert(spd_text.size() == 11);
    return {spd_row<0>(), spd_row<1>(), spd_row<2>(), spd_row<3>(), spd_row<4>(), spd_row<5>(),
            spd_row<6>(), spd_row<7>(), spd_row<8>(), spd_row<9>(), spd_row<10>()};
}

}  // namespace rtlab::gen
