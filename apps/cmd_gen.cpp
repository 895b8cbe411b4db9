// rtlab gen: writes a procedural scene (SPD sphere flake and family, stress scenes) as scene JSON
// with its meshes beside it, or as one mesh file when the output has a mesh extension.
#include "apps/commands.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "datasets_gen/generators.h"
#include "datasets_gen/memory_guard.h"
#include "datasets_gen/spd_databases.h"
#include "mesh/mesh_io.h"
#include "scene/nff_io.h"
#include "scene/scene_io.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace rtlab::app {

namespace {

struct GenArgs {
    CLI::Option* tess_opt = nullptr;
    std::string name;
    int size = -1;
    std::string as = "spheres";
    std::string tess = "uv:16x8";
    std::uint64_t seed = 1;
    std::uint64_t max_memory_mib = 0;
    std::string out;
    bool list = false;
};

void print_list() {
    std::cout << fmt::format("{:<15} {:>4} {:>5} {:>4}  {}\n", "name", "min", "def", "max",
                             "description / count formula");
    for (const gen::Generator& g : gen::generators()) {
        std::cout << fmt::format("{:<15} {:>4} {:>5} {:>4}  {}\n{:<32}{}\n", g.name, g.min_size,
                                 g.default_size, g.max_size, g.description, "", g.count_formula);
    }
}

int run_gen(const GenArgs& a) {
    if (a.list) {
        print_list();
        return 0;
    }
    if (a.name.empty()) {
        throw Error("gen: a generator name is required (see rtlab gen --list)");
    }
    if (a.out.empty()) {
        throw Error("gen: --out/-o is required");
    }
    const gen::Generator* g = gen::find_generator(a.name);
    if (g == nullptr) {
        throw Error("gen: unknown generator '" + a.name + "' (see rtlab gen --list)");
    }
    const std::filesystem::path out(a.out);
    const bool mesh_file = is_mesh_path(out);
    const bool nff_file = out.extension() == ".nff";
    if (!mesh_file && !nff_file && out.extension() != ".json") {
        throw Error(out.string() +
                    ": output must be .json, .nff or a mesh file (.ply .obj .off .stl)");
    }
    if (a.tess_opt->count() > 0 && !mesh_file && a.as != "mesh") {
        throw Error(
            "gen: --tess only applies to tessellated spheres (--as mesh or a mesh output "
            "file)");
    }
    check_output_path(out);
    gen::GenOptions o;
    o.size = a.size;
    o.as_mesh = mesh_file || a.as == "mesh";
    o.tess = gen::parse_sphere_tess(a.tess);
    o.seed = a.seed;
    o.memory_limit = gen::saturating_mul(a.max_memory_mib, std::uint64_t{1} << 20);
    const Scene s = gen::generate(*g, o);
    if (nff_file) {
        // SPD databases are written record for record as the SPD program prints them (cones and
        // patch normals included); other generators through their scene.
        const gen::spd::Database* db = gen::spd::find_database(g->name);
        const nff::Document d = db != nullptr && !o.as_mesh
                                    ? db->document(o.size < 0 ? g->default_size : o.size)
                                    : nff::from_scene(s);
        nff::save(d, out);
        const nff::Counts c = nff::count(d);
        std::cout << fmt::format(
            "{}: {} spheres, {} cones, {} polygons, {} patches, {} lights -> {}\n", g->name,
            c.spheres, c.cones, c.polygons, c.patches, c.lights, out.string());
    } else if (mesh_file) {
        const TriangleMesh m = gen::scene_to_mesh(s, o.tess);
        save_mesh(m, out);
        std::cout << fmt::format("{}: {} triangles, {} vertices -> {}\n", g->name,
                                 m.triangle_count(), m.vertex_count(), out.string());
    } else {
        save_scene(s, out, true);
        std::size_t triangles = 0;
        for (const MeshObject& m : s.meshes) {
            triangles += m.mesh.triangle_count();
        }
        std::cout << fmt::format("{}: {} spheres, {} cones, {} triangles, {} polygons -> {}\n",
                                 g->name, s.spheres.size(), s.cones.size(), triangles,
                                 s.polygons.size(), out.string());
    }
    return 0;
}

}  // namespace

Command add_gen(CLI::App& root) {
    auto args = std::make_shared<GenArgs>();
    CLI::App* sub = root.add_subcommand(
        "gen",
        "Generate a procedural scene (SPD sphere flake and family, stress scenes) as scene JSON "
        "with meshes beside it, or as one mesh file (.ply .obj .off .stl; spheres tessellated)");
    sub->add_option("name", args->name, "Generator name (see --list)");
    sub->add_flag("--list", args->list, "List the generators with their size formulas");
    sub->add_option("--size", args->size, "Size factor SF (default: the generator's)")
        ->check(CLI::Range(0, 64));
    sub->add_option("--as", args->as, "Spheres as analytic spheres or tessellated meshes")
        ->check(CLI::IsMember({"spheres", "mesh"}));
    args->tess_opt = sub->add_option("--tess", args->tess,
                                     "Sphere tessellation: uv:UxV or cube:N (default uv:16x8)");
    sub->add_option("--seed", args->seed, "Seed of the random generators (default 1)");
    sub->add_option("--max-memory", args->max_memory_mib,
                    "Refuse sizes whose estimate exceeds this many MiB (default half of RAM)");
    sub->add_option("-o,--out", args->out,
                    "Output: .json scene, .nff (NFF, as the SPD writes it) or a mesh file");
    return {sub, [args] { return run_gen(*args); }};
}

}  // namespace rtlab::app
