// rtlab: the command line. One subcommand per job; errors are one line on stderr and a non-zero
// exit code, never a crash or a half-written file.
#include "apps/commands.h"
#include "base/atomic_file.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

namespace {

/// Levenshtein distance (for "did you mean").
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) {
        row[j] = j;
    }
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

/// The one-line error for a first argument that is not a subcommand, or "" when it is one.
std::string unknown_command(std::string_view arg,
                            const std::vector<rtlab::app::Command>& commands) {
    std::string names;
    std::string best;
    std::size_t best_distance = 3;  // suggest only within two edits
    for (const rtlab::app::Command& c : commands) {
        const std::string& name = c.sub->get_name();
        if (name == arg) {
            return "";
        }
        names += (names.empty() ? "" : ", ") + name;
        const std::size_t d = edit_distance(arg, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    std::string msg = "rtlab: unknown command '" + std::string(arg) + "'";
    msg += best.empty() ? " (commands: " + names + ")" : "; did you mean '" + best + "'?";
    return msg;
}

/// The message as one printable line: control bytes (newlines included) and bytes that are not
/// part of valid UTF-8 become \xNN, so file contents quoted in a message cannot break the line or
/// the terminal.
std::string one_line(std::string_view s) {
    std::string out;
    const auto hex = [&out](unsigned char c) {
        static constexpr char digits[] = "0123456789abcdef";
        out += "\\x";
        out += digits[c >> 4];
        out += digits[c & 15];
    };
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x20 || c == 0x7f) {
            hex(c);
            ++i;
            continue;
        }
        const std::size_t n = c < 0x80         ? 1
                              : (c >> 5) == 6  ? 2
                              : (c >> 4) == 14 ? 3
                              : (c >> 3) == 30 ? 4
                                               : 0;
        bool valid = n > 0 && i + n <= s.size() && (n != 2 || c >= 0xc2);
        for (std::size_t k = 1; valid && k < n; ++k) {
            valid = (static_cast<unsigned char>(s[i + k]) >> 6) == 2;
        }
        if (!valid) {
            hex(c);
            ++i;
            continue;
        }
        out.append(s.substr(i, n));
        i += n;
    }
    return out;
}

}  // namespace

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

    rtlab::install_interrupt_cleanup("rtlab");
    if (argc >= 2 && argv[1][0] != '-') {
        const std::string unknown = unknown_command(argv[1], commands);
        if (!unknown.empty()) {
            std::cerr << unknown << " (see rtlab --help)\n";
            return 2;
        }
    }
    try {
        root.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return root.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "rtlab: " << one_line(e.what()) << " (see rtlab --help)\n";
        return 2;
    }

    try {
        for (const rtlab::app::Command& c : commands) {
            if (c.sub->parsed()) {
                return c.run();
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "rtlab: " << one_line(e.what()) << "\n";
        return 1;
    }
    return 2;
}
