// The optional "renders" and "crosscheck" lists of a sweep file.
#include "crosscheck/crosscheck.h"
#include "render/renderer.h"
#include "sweep/json_read.h"
#include "sweep/sweep_file.h"

#include <algorithm>
#include <set>

namespace rtlab::sweep {

using namespace detail;

namespace {

// A list of non-empty strings (or one string), each checked by ok(name); none twice.
template <class Ok>
std::vector<std::string> string_list(const ojson& v,
                                     const std::string& where,
                                     const char* what,
                                     Ok ok) {
    std::vector<std::string> out;
    for (const ojson& x : as_list(v)) {
        std::string name = get_string(x, where);
        if (std::string err = ok(name); !err.empty()) {
            fail(where, fmt::format("unknown {} '{}' ({})", what, name, err));
        }
        if (std::find(out.begin(), out.end(), name) != out.end()) {
            fail(where, fmt::format("{} '{}' twice", what, name));
        }
        out.push_back(std::move(name));
    }
    if (out.empty()) {
        fail(where, "an empty list");
    }
    return out;
}

RenderRows parse_render(const ojson& r, const std::string& where, const SweepFile& s) {
    if (!r.is_object()) {
        fail(where, "expected {\"scenes\": [...], \"structures\": [...], \"aov\": [...], ...}");
    }
    RenderRows out;
    out.specs = s.specs;
    out.aovs = {"color"};
    for (const auto& [k, v] : r.items()) {
        const std::string w = where + "." + k;
        if (k == "scenes") {
            std::string labels;
            for (const SceneSource& src : s.scenes) {
                labels += fmt::format("{}{}", labels.empty() ? "" : " ", src.label);
            }
            for (const std::string& name : string_list(v, w, "scene", [&](const std::string& n) {
                     const bool known = std::any_of(s.scenes.begin(), s.scenes.end(),
                                                    [&](const auto& x) { return x.label == n; });
                     return known ? std::string() : "the sweep's scenes: " + labels;
                 })) {
                for (std::size_t i = 0; i < s.scenes.size(); ++i) {
                    if (s.scenes[i].label == name) {
                        out.scenes.push_back(i);
                    }
                }
            }
        } else if (k == "structures") {
            out.specs.clear();
            const std::vector<ojson> entries = as_list(v);
            for (std::size_t i = 0; i < entries.size(); ++i) {
                for (std::string& spec :
                     expand_structure(entries[i], fmt::format("{}[{}]", w, i))) {
                    out.specs.push_back(std::move(spec));
                }
            }
            if (out.specs.empty()) {
                fail(w, "an empty list");
            }
        } else if (k == "aov") {
            out.aovs = string_list(v, w, "aov", [](const std::string& n) {
                try {
                    (void)parse_aov(n);
                    return std::string();
                } catch (const std::exception&) {
                    return std::string("color depth normal heatmap");
                }
            });
        } else if (k == "width") {
            out.width = static_cast<int>(get_int(v, w, 1, 16384));
        } else if (k == "height") {
            out.height = static_cast<int>(get_int(v, w, 1, 16384));
        } else if (k == "depth") {
            out.max_depth = static_cast<int>(get_int(v, w, 0, 64));
        } else {
            fail(w, "unknown key (render keys: scenes structures aov width height depth)");
        }
    }
    if (out.scenes.empty()) {
        for (std::size_t i = 0; i < s.scenes.size(); ++i) {
            out.scenes.push_back(i);
        }
    }
    return out;
}

CrosscheckRows parse_crosscheck(const ojson& r, const std::string& where) {
    if (!r.is_object() || !r.contains("prim")) {
        fail(where, "expected {\"prim\": KIND, \"methods\": [...], \"precision\": [...], ...}");
    }
    CrosscheckRows out;
    std::string kinds;
    for (const xcheck::PrimCheck& c : xcheck::prim_checks()) {
        kinds += fmt::format("{}{}", kinds.empty() ? "" : " ", c.prim);
    }
    out.prim = get_string(r["prim"], where + ".prim");
    const xcheck::PrimCheck* check = xcheck::find_prim_check(out.prim);
    if (check == nullptr) {
        fail(where + ".prim", fmt::format("unknown primitive kind '{}' ({})", out.prim, kinds));
    }
    const std::vector<std::string> known = check->methods();
    out.methods = known;
    out.precisions = {"float", "double"};
    for (const auto& [k, v] : r.items()) {
        const std::string w = where + "." + k;
        if (k == "prim") {
            continue;
        }
        if (k == "methods") {
            out.methods = string_list(v, w, "method", [&](const std::string& n) {
                std::string names;
                for (const std::string& m : known) {
                    names += fmt::format("{}{}", names.empty() ? "" : " ", m);
                }
                return std::find(known.begin(), known.end(), n) != known.end()
                           ? std::string()
                           : out.prim + " methods: " + names;
            });
        } else if (k == "precision") {
            out.precisions = string_list(v, w, "precision", [](const std::string& n) {
                return n == "float" || n == "double" ? std::string() : std::string("float double");
            });
        } else if (k == "rays") {
            out.rays = static_cast<std::size_t>(get_int(v, w, 1, 100000000));
        } else if (k == "seed") {
            out.seed = static_cast<std::uint64_t>(get_int(v, w, 0, INT64_MAX));
        } else {
            fail(w, "unknown key (crosscheck keys: prim methods precision rays seed)");
        }
    }
    return out;
}

}  // namespace

std::vector<RenderRows> parse_renders(const ojson& list,
                                      const std::string& where,
                                      const SweepFile& s) {
    std::vector<RenderRows> out;
    const std::vector<ojson> entries = as_list(list);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        out.push_back(parse_render(entries[i], fmt::format("{}[{}]", where, i), s));
    }
    return out;
}

std::vector<CrosscheckRows> parse_crosschecks(const ojson& list, const std::string& where) {
    std::vector<CrosscheckRows> out;
    const std::vector<ojson> entries = as_list(list);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        out.push_back(parse_crosscheck(entries[i], fmt::format("{}[{}]", where, i)));
    }
    return out;
}

}  // namespace rtlab::sweep
