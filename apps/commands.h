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

}  // namespace rtlab::app
