// rtlab list: the registered structures with their parameters, and the intersection methods per
// primitive family; as text or as JSON.
#include "accel/any_accel.h"
#include "apps/commands.h"
#include "trace/prim_sets.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rtlab::app {

namespace {

std::string_view kind_name(ParamKind k) {
    switch (k) {
    case ParamKind::integer:
        return "integer";
    case ParamKind::real:
        return "real";
    case ParamKind::choice:
        return "choice";
    }
    return "?";
}

nlohmann::json list_json() {
    nlohmann::json j;
    j["structures"] = nlohmann::json::array();
    for (const AccelEntry& e : accel_registry()) {
        nlohmann::json row;
        row["name"] = e.name;
        row["description"] = e.description;
        row["default_spec"] = default_spec(e).canonical();
        row["params"] = nlohmann::json::array();
        for (const ParamSpec& p : e.params) {
            nlohmann::json q;
            q["key"] = p.key;
            q["kind"] = kind_name(p.kind);
            q["default"] = p.format(p.default_value);
            q["range"] = p.range_text();
            q["help"] = p.help;
            // Where the key takes effect: always (null), or with these values of another key.
            q["needs"] = nullptr;
            if (!p.needs.empty()) {
                q["needs"] = {{"key", p.needs}, {"values", p.needs_values}};
            }
            q["build_only"] = p.build_only;
            q["tracer_only"] = p.tracer_only;
            row["params"].push_back(q);
        }
        j["structures"].push_back(row);
    }
    j["methods"] = nlohmann::json::object();
    for (const MethodFamily& f : method_families()) {
        j["methods"][std::string(f.family)] = f.methods;
    }
    return j;
}

void list_text() {
    std::cout << "structures (--accel NAME[,key=value]...):\n";
    for (const AccelEntry& e : accel_registry()) {
        std::cout << fmt::format("  {:<16} {}\n", e.name, e.description);
        for (const ParamSpec& p : e.params) {
            std::string help(p.help);
            if (!p.needs.empty()) {
                help += fmt::format(" [only with {}]", p.needs_text());
            }
            if (p.build_only) {
                help += " [build only: the same structure for any value]";
            }
            if (p.tracer_only) {
                help += " [tracer only: the same structure for any value]";
            }
            std::cout << fmt::format("    {:<12} {:<8} default {:<6} {:<22} {}\n", p.key,
                                     kind_name(p.kind), p.format(p.default_value), p.range_text(),
                                     help);
        }
    }
    std::cout << "methods (--method), default first:\n";
    for (const MethodFamily& f : method_families()) {
        std::cout << fmt::format("  {:<10}", f.family);
        for (std::string_view m : f.methods) {
            std::cout << " " << m;
        }
        std::cout << "\n";
    }
}

}  // namespace

Command add_list(CLI::App& root) {
    auto json = std::make_shared<bool>(false);
    auto names = std::make_shared<bool>(false);
    CLI::App* sub = root.add_subcommand(
        "list",
        "List the acceleration structures (--accel) with their parameters, defaults and ranges, "
        "and the intersection methods (--method)");
    sub->add_flag("--json", *json, "Print the same as one JSON object");
    sub->add_flag("--names", *names, "Print only the structure names, one per line (for scripts)")
        ->excludes("--json");
    return {sub, [json, names] {
                if (*names) {
                    for (const AccelEntry& e : accel_registry()) {
                        std::cout << e.name << "\n";
                    }
                } else if (*json) {
                    std::cout << list_json().dump(2) << "\n";
                } else {
                    list_text();
                }
                return 0;
            }};
}

}  // namespace rtlab::app
