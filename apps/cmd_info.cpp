// rtlab info: what a scene or mesh file holds - counts per primitive type, bounds, mesh statistics
// (closed or not, boundary / non-manifold edges, degenerate faces) and the features it uses.
#include "apps/commands.h"
#include "mesh/mesh_stats.h"
#include "scene/scene_io.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rtlab::app {

namespace {

struct InfoArgs {
    std::string file;
    bool json = false;
};

std::string vec_text(const Vec3f& v) {
    return fmt::format("[{:g}, {:g}, {:g}]", v.x, v.y, v.z);
}

nlohmann::ordered_json vec_json(const Vec3f& v) {
    return nlohmann::ordered_json::array(
        {static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)});
}

nlohmann::ordered_json stats_json(const MeshStats& st) {
    return {{"vertices", st.vertices},
            {"triangles", st.triangles},
            {"closed", st.closed},
            {"edges", st.edges},
            {"boundary_edges", st.boundary_edges},
            {"non_manifold_edges", st.non_manifold_edges},
            {"inconsistent_edges", st.inconsistent_edges},
            {"degenerate_triangles", st.degenerate_triangles},
            {"duplicate_triangles", st.duplicate_triangles},
            {"unreferenced_vertices", st.unreferenced_vertices}};
}

int run_info(const InfoArgs& a) {
    const Scene s = load_scene(a.file);
    std::array<std::size_t, prim_type_count> counts{};
    for (const ObjectRef& r : s.order) {
        ++counts[static_cast<std::size_t>(r.type)];
    }
    const std::uint32_t primitives = primitive_id_base(s).back();
    const Bounds3f b = scene_bounds(s);
    const std::vector<std::string> feats = feature_names(features(s));
    std::vector<MeshStats> stats;
    for (const MeshObject& m : s.meshes) {
        stats.push_back(mesh_stats(m.mesh));
    }

    if (a.json) {
        nlohmann::ordered_json j;
        j["file"] = a.file;
        j["objects"] = nlohmann::ordered_json::object();
        for (std::size_t t = 0; t < prim_type_count; ++t) {
            j["objects"][std::string(to_string(static_cast<PrimType>(t)))] = counts[t];
        }
        j["primitives"] = primitives;
        j["bounds"] =
            b.empty() ? nlohmann::ordered_json(nullptr)
                      : nlohmann::ordered_json{{"min", vec_json(b.lo)}, {"max", vec_json(b.hi)}};
        j["meshes"] = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < s.meshes.size(); ++i) {
            nlohmann::ordered_json m = stats_json(stats[i]);
            m["file"] = s.meshes[i].file;
            j["meshes"].push_back(m);
        }
        j["lights"] = s.lights.size();
        j["materials"] = s.materials.size();
        j["camera"] = {{"from", vec_json(s.camera.from)},
                       {"at", vec_json(s.camera.at)},
                       {"fov_deg", static_cast<double>(s.camera.fov_deg)},
                       {"width", s.camera.width},
                       {"height", s.camera.height}};
        j["features"] = feats;
        std::cout << j.dump() << "\n";
        return 0;
    }

    std::cout << fmt::format("file:        {}\n", a.file);
    std::cout << fmt::format("objects:     {} ({} primitives)\n", s.order.size(), primitives);
    for (std::size_t t = 0; t < prim_type_count; ++t) {
        if (counts[t] > 0) {
            std::cout << fmt::format("  {:<9}  {}\n", to_string(static_cast<PrimType>(t)),
                                     counts[t]);
        }
    }
    if (b.empty()) {
        std::cout << "bounds:      (empty)\n";
    } else {
        std::cout << fmt::format("bounds:      {} .. {}\n", vec_text(b.lo), vec_text(b.hi));
    }
    for (std::size_t i = 0; i < s.meshes.size(); ++i) {
        const MeshStats& st = stats[i];
        std::cout << fmt::format(
            "mesh {} ({}): {} triangles, {} vertices, {}; boundary edges {}, non-manifold edges "
            "{}, inconsistently oriented edges {}, degenerate triangles {}, duplicate triangles "
            "{}, unreferenced vertices {}\n",
            i, s.meshes[i].file.empty() ? "-" : s.meshes[i].file, st.triangles, st.vertices,
            st.closed ? "closed" : "open", st.boundary_edges, st.non_manifold_edges,
            st.inconsistent_edges, st.degenerate_triangles, st.duplicate_triangles,
            st.unreferenced_vertices);
    }
    std::cout << fmt::format("lights:      {}\nmaterials:   {}\n", s.lights.size(),
                             s.materials.size());
    std::cout << fmt::format("camera:      from {} at {}, fov {:g} deg, {}x{}\n",
                             vec_text(s.camera.from), vec_text(s.camera.at), s.camera.fov_deg,
                             s.camera.width, s.camera.height);
    std::cout << fmt::format("features:    {}\n", feats.empty()
                                                      ? std::string("(none)")
                                                      : fmt::format("{}", fmt::join(feats, " ")));
    return 0;
}

}  // namespace

Command add_info(CLI::App& root) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* sub = root.add_subcommand(
        "info",
        "Describe a scene (.json) or mesh (.obj .ply .off .stl): counts per primitive type, "
        "bounds, mesh statistics (closed, boundary / non-manifold edges, degenerate faces) and "
        "the features the scene uses");
    sub->add_option("file", args->file, "Scene or mesh file")->required();
    sub->add_flag("--json", args->json, "Print one JSON object instead of text");
    return {sub, [args] { return run_info(*args); }};
}

}  // namespace rtlab::app
