#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the root CLI11 app;
// main() lists the registrations.

#include <functional>

namespace CLI {
class App;
}

namespace rtlab::app {

/// A registered subcommand: its CLI11 node and what to run when it was parsed (returns the exit
/// code; throws std::exception for a one-line error).
struct Command {
    CLI::App* sub;
    std::function<int()> run;
};

/// `rtlab crosscheck`: every intersection method against CGAL's exact predicates.
Command add_crosscheck(CLI::App& root);

/// `rtlab rays`: deterministic ray sets for a scene.
Command add_rays(CLI::App& root);

/// `rtlab trace`: traces a ray file through a scene, prints one JSON object.
Command add_trace(CLI::App& root);

/// `rtlab compare`: compares two hit files.
Command add_compare(CLI::App& root);

/// `rtlab list`: structures and intersection methods.
Command add_list(CLI::App& root);

/// `rtlab gen`: procedural scenes (sphere flake, SPD family, stress scenes) to scene JSON or a
/// mesh.
Command add_gen(CLI::App& root);

/// `rtlab render`: the Whitted ray tracer, writes a PNG or EXR image.
Command add_render(CLI::App& root);

/// `rtlab info`: counts, bounds, mesh statistics and features of a scene or mesh file.
Command add_info(CLI::App& root);

/// `rtlab sweep`: experiment sweeps from a JSON file, run here or as a Slurm job array.
Command add_sweep(CLI::App& root);

/// `rtlab stability`: the numerical-stability suite and its report.
Command add_stability(CLI::App& root);

}  // namespace rtlab::app
