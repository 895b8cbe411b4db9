// rtlab: the command line. One subcommand per job; errors are one line on stderr and a non-zero
// exit code, never a crash or a half-written file.
#include "apps/commands.h"

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    CLI::App root{"rtlab: a testbed for ray-tracing acceleration structures and intersectors"};
    root.require_subcommand(1);
#ifdef NDEBUG
    constexpr const char* build = "release";
#else
    constexpr const char* build = "debug";
#endif
    root.set_version_flag("--version", std::string("rtlab 0.1.0 (") + build + ", " +
#ifdef __clang__
                                           "clang "
#else
                                           "g++ "
#endif
                                           __VERSION__ +
                                           ")");

    const std::vector<rtlab::app::Command> commands{
        rtlab::app::add_crosscheck(root), rtlab::app::add_rays(root),
        rtlab::app::add_trace(root),      rtlab::app::add_compare(root),
        rtlab::app::add_list(root),       rtlab::app::add_info(root),
        rtlab::app::add_gen(root),        rtlab::app::add_stability(root),
        rtlab::app::add_render(root),     rtlab::app::add_sweep(root),
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
