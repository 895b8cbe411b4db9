// rtlab list: the registered structures and the intersection methods per primitive family.
#include "accel/any_accel.h"
#include "apps/commands.h"
#include "trace/prim_sets.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>

namespace rtlab::app {

Command add_list(CLI::App& root) {
    CLI::App* sub = root.add_subcommand(
        "list", "List the acceleration structures (--accel) and intersection methods (--method)");
    return {sub, [] {
                std::cout << "structures (--accel):\n";
                for (const AccelEntry& e : accel_registry()) {
                    std::cout << fmt::format("  {:<16} {}\n", e.name, e.description);
                }
                std::cout << "methods (--method), default first:\n";
                for (const MethodFamily& f : method_families()) {
                    std::cout << fmt::format("  {:<10}", f.family);
                    for (std::string_view m : f.methods) {
                        std::cout << " " << m;
                    }
                    std::cout << "\n";
                }
                return 0;
            }};
}

}  // namespace rtlab::app
