#pragma once
// The sweep file (docs/sweeps.md): JSON with comments naming scenes, structure specs with
// parameter lists, methods, ray kinds and counts, thread counts, repetitions and a seed. Loading
// validates everything that can be checked without running (generators and their sizes, scene
// files, spec names and keys through the registry's ParamSpecs, method names, ray kinds), so a
// typo fails before any case runs.

#include "scene/scene.h"

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtlab::sweep {

/// One scene of a sweep: a generator with its options, or a scene/mesh file.
struct SceneSource {
    std::string label;      ///< "name" from the file, else the key
    std::string key;        ///< canonical description, part of the case ids
    std::string generator;  ///< generator name; empty for a file
    int size = -1;          ///< generator size factor (-1: the generator's default)
    bool as_mesh = false;   ///< tessellate analytic spheres
    std::string tess = "uv:16x8";
    std::uint64_t seed = 1;      ///< generator seed
    std::string file;            ///< the file as written in the sweep file
    std::filesystem::path path;  ///< the file resolved against the sweep file's folder
};

/// A `renders` entry: each listed scene rendered with each listed structure spec, for each AOV.
struct RenderRows {
    std::vector<std::size_t> scenes;  ///< indices into SweepFile::scenes
    std::vector<std::string> specs;   ///< canonical specs
    std::vector<std::string> aovs;    ///< color depth normal heatmap
    int width = 128;
    int height = 128;
    int max_depth = 5;
};

/// A `crosscheck` entry: methods of one primitive kind in each precision against the exact oracle
/// (`rtlab crosscheck`), one case per method and precision.
struct CrosscheckRows {
    std::string prim;
    std::vector<std::string> methods;     ///< method names of the kind (every one by default)
    std::vector<std::string> precisions;  ///< float double
    std::size_t rays = 10000;
    std::uint64_t seed = 1;
};

/// A loaded, validated sweep file.
struct SweepFile {
    std::string name = "sweep";
    std::uint64_t seed = 1;  ///< ray-set seed
    std::vector<SceneSource> scenes;
    std::vector<std::string> specs;    ///< canonical specs, parameter lists expanded, file order
    std::vector<std::string> methods;  ///< method lists ("a,b"); "" is every family's default
    std::vector<std::string> kinds;    ///< ray kinds; shadow rays are traced as any-hit queries
    std::size_t ray_count = 10000;
    std::vector<int> threads{0};  ///< 0: every core the run has (its allocation on Slurm)
    int repeat = 3;               ///< timed runs per case; the median is reported
    int warmup = 1;               ///< untimed runs before them
    bool stats = true;            ///< counting pass (nodes/ray, prims/ray)
    bool robust = false;          ///< conservative box tests in traversal
    bool exact = false;           ///< certified triangle hits (rtlab trace --exact)
    std::vector<RenderRows> renders;
    std::vector<CrosscheckRows> crosschecks;
    /// The file as loaded (comments dropped) plus "base_dir", the folder scene files are
    /// resolved against: what a sweep folder keeps as sweep.json, and how two files compare.
    nlohmann::ordered_json normalized;
};

/// Generates or loads the scene `src` names (rtlab::Error when it cannot).
Scene make_scene(const SceneSource& src);

/// Loads and validates a sweep file; throws rtlab::Error with one line naming the file and the
/// place ("sweep.json: structures[1].max_leaf: ...").
SweepFile load_sweep_file(const std::filesystem::path& file);

/// Parses the "renders" list (scenes named by their labels, default all; structures as in
/// "structures", default the sweep's specs). Throws rtlab::Error naming `where`.
std::vector<RenderRows> parse_renders(const nlohmann::ordered_json& list,
                                      const std::string& where,
                                      const SweepFile& s);

/// Parses the "crosscheck" list. Throws rtlab::Error naming `where`.
std::vector<CrosscheckRows> parse_crosschecks(const nlohmann::ordered_json& list,
                                              const std::string& where);

/// Expands one structure entry: a spec string, or {"spec": S, key: value-or-list, ...} whose
/// lists multiply out (first key outermost). Returns canonical specs; throws rtlab::Error naming
/// `where` for a bad spec, key or value.
std::vector<std::string> expand_structure(const nlohmann::ordered_json& entry,
                                          const std::string& where);

}  // namespace rtlab::sweep
