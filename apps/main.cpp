// rtlab: the command line. One subcommand per job; errors are one line on stderr and a non-zero
// exit code, never a crash or a half-written file.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <vector>

#include "apps/commands.h"

int main(int argc, char** argv) {
    CLI::App root{"rtlab: a testbed for ray-tracing acceleration structures and intersectors"};
    root.require_subcommand(1);
    root.set_version_flag("--version", "rtlab 0.1.0");

    const std::vector<rtlab::app::Command> commands{
        rtlab::app::add_crosscheck(root),
    };

    try {
        root.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return root.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "rtlab: " << e.what() << " (see rtlab --help)\n";
        return 2;
    }

    try {
        for (const rtlab::app::Command& c : commands) {
            if (c.sub->parsed()) {
                return c.run();
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "rtlab: " << e.what() << "\n";
        return 1;
    }
    return 2;
}
