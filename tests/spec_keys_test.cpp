// A spec records only what takes effect: for every registry row, in every context (the defaults,
// and each value of each choice parameter), moving a key the spec accepts changes the structure
// or what the tracer reads of the spec (slot_ordered_leaves); a build-only key such as threads
// changes neither, a tracer-only one such as a kd-tree's leaves only the tracer's part; a key the
// spec refuses as having no effect indeed builds the same structure. The canonical spec names
// exactly the accepted keys.

#include "accel/any_accel.h"
#include "support/accel_fixtures.h"
#include "trace/clip.h"

#include <catch2/catch.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace rtlab {
namespace {

/// What every case builds from: 1000 seeded random triangles, with exact clipping (kd-tree perfect
/// splits) and exact diagonal extents (`bounds=dop14`), so every key that can read the primitives
/// does; and 1000 random boxes, whose duplicates and point boxes reach the corners of a cost
/// model (a kd-tree node of two primitives on one side of its median) the triangles may not.
std::vector<BuildInput> inputs() {
    static const test::Soup tris = test::random_soup(test::SoupKind::triangles, 7, 1000);
    static const test::Soup boxes = test::random_soup(test::SoupKind::boxes, 7, 1000);
    BuildInput t = tris.input();
    t.clip = [](std::uint32_t id, const Bounds3f& box) {
        const auto& p = tris.triangles[id];
        return clip_shape_bounds(Trianglef{p.p0, p.p1, p.p2}, box);
    };
    return {t, boxes.input()};
}

/// Builds spec (text or parsed) from every input.
template <class Spec>
std::vector<AnyAccel> build_all(const Spec& spec, const std::vector<BuildInput>& in) {
    std::vector<AnyAccel> out;
    for (const BuildInput& i : in) {
        out.push_back(build_accel(spec, i));
    }
    return out;
}

/// The structure without the copies of its build settings kept only for reports (a BVH's
/// Config, a kd-tree's cost constants and depth limit): what traversal reads.
AnyAccel without_settings(AnyAccel a) {
    std::visit(
        [](auto& s) {
            if constexpr (requires { s.config; }) {
                s.config = {};
            }
            if constexpr (std::is_same_v<std::decay_t<decltype(s)>, KdTree>) {
                s.traversal_cost = 0;
                s.intersection_cost = 0;
                s.max_depth = 0;
            }
        },
        a);
    return a;
}

/// The values a test moves parameter p to from its default v: the minimum (when that is the
/// default, the next integer, or for a real the maximum), then the maximum; every other choice of
/// a choice parameter. One value may leave a particular tree alone (ci=0.001 on the wide layouts:
/// with ct=4 and blocks of 4 every range of up to max_leaf becomes a leaf for any ci below 2), so
/// a key takes effect when any of them changes the structure.
std::vector<double> moves(const ParamSpec& p, double v) {
    std::vector<double> out;
    if (p.kind == ParamKind::choice) {
        for (std::size_t c = 0; c < p.choices.size(); ++c) {
            if (static_cast<double>(c) != v) {
                out.push_back(static_cast<double>(c));
            }
        }
        return out;
    }
    if (p.min != v) {
        out.push_back(p.min);
    } else if (p.kind == ParamKind::integer && p.min + 1 < p.max) {
        out.push_back(p.min + 1);
    }
    if (p.max != v) {
        out.push_back(p.max);
    }
    return out;
}

/// The spec text `base` with ",key=value" appended.
std::string with_key(const std::string& base, const ParamSpec& p, double v) {
    return base + "," + std::string(p.key) + "=" + p.format(v);
}

/// The message parse_accel_spec throws for text, or "" when it accepts it.
std::string refusal(const std::string& text) {
    try {
        parse_accel_spec(text);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

/// The contexts of row e: the bare name, and name,KEY=VALUE for each non-default value of each
/// choice parameter the defaults let take effect.
std::vector<std::string> contexts(const AccelEntry& e) {
    std::vector<std::string> out{std::string(e.name)};
    for (const ParamSpec& p : e.params) {
        if (p.kind != ParamKind::choice) {
            continue;
        }
        for (std::size_t c = 0; c < p.choices.size(); ++c) {
            const std::string text = with_key(std::string(e.name), p, static_cast<double>(c));
            if (static_cast<double>(c) != p.default_value && refusal(text).empty()) {
                out.push_back(text);
            }
        }
    }
    return out;
}

/// The key `text` sets last (contexts set at most one).
std::string_view context_key(const std::string& text) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) {
        return {};
    }
    const std::string_view kv = std::string_view(text).substr(comma + 1);
    return kv.substr(0, kv.find('='));
}

/// A key whose effect shows only with another setting off its default, which no choice of the
/// row expresses: the test moves it with `setting` added to the context.
struct ShownWith {
    std::string_view row;
    std::string_view key;
    std::string_view setting;
};

// At the default costs (K_T 1, K_I 1.5) the spatial median splits every node of three or more
// primitives whatever the empty-space bonus (a half box has at most 2/3 of its node's area, so
// 1 + 1.5 * 2/3 * n < 1.5 * n), and a node of two only when it is a cube; with a dearer node step
// the bonus decides which nodes split.
constexpr ShownWith shown_with[] = {{"kdtree:median", "empty_bonus", "ct=10"}};

/// The setting the test adds to show key's effect on row (shown_with), or "".
std::string_view setting_for(std::string_view row, std::string_view key) {
    for (const ShownWith& s : shown_with) {
        if (s.row == row && s.key == key) {
            return s.setting;
        }
    }
    return {};
}

/// The keys the canonical spec `text` names, in order.
std::vector<std::string> canonical_keys(const std::string& text) {
    std::vector<std::string> keys;
    std::size_t at = text.find(',');
    while (at != std::string::npos) {
        const std::size_t eq = text.find('=', at);
        keys.push_back(text.substr(at + 1, eq - at - 1));
        at = text.find(',', eq);
    }
    return keys;
}

// Hundreds of builds (every row, context and key at both ends of its range): about 10 s in
// release and over 10 minutes under asan, so it runs with the slow tests in the release build.
TEST_CASE("every key a spec accepts takes effect, every key it refuses has none",
          "[accel][spec][.slow]") {
    const std::vector<BuildInput> in = inputs();
    for (const AccelEntry& e : accel_registry()) {
        for (const std::string& context : contexts(e)) {
            CAPTURE(context);
            const AccelSpec base_spec = parse_accel_spec(context);
            const std::vector<AnyAccel> base = build_all(base_spec, in);
            std::vector<AnyAccel> base_plain;
            for (const AnyAccel& a : base) {
                base_plain.push_back(without_settings(a));
            }
            std::vector<std::string> accepted;
            for (std::size_t i = 0; i < e.params.size(); ++i) {
                const ParamSpec& p = e.params[i];
                CAPTURE(p.key);
                if (p.key == context_key(context)) {
                    accepted.emplace_back(p.key);
                    continue;
                }
                std::size_t refused = 0;
                bool changed = false;         // some structure differs from the context's
                bool tracer_changed = false;  // the tracer's leaf policy differs
                std::vector<double> values = moves(p, p.default_value);
                if (p.build_only) {
                    values.resize(1);  // threads=1 against all; not 256 threads on a small machine
                }
                const std::string_view setting = setting_for(e.name, p.key);
                std::vector<AnyAccel> shown_base;
                if (!setting.empty()) {
                    for (const AnyAccel& a : build_all(context + "," + std::string(setting), in)) {
                        shown_base.push_back(without_settings(a));
                    }
                }
                for (const double v : values) {
                    const std::string text = with_key(context, p, v);
                    CAPTURE(text);
                    const std::string why = refusal(text);
                    if (why.empty()) {
                        const std::vector<AnyAccel> a = build_all(text, in);
                        if (p.build_only) {
                            CHECK(a == base);
                        }
                        for (std::size_t k = 0; k < in.size(); ++k) {
                            changed = changed || !(without_settings(a[k]) == base_plain[k]);
                        }
                        if (!setting.empty()) {
                            const std::vector<AnyAccel> b =
                                build_all(text + "," + std::string(setting), in);
                            for (std::size_t k = 0; k < in.size(); ++k) {
                                changed = changed || !(without_settings(b[k]) == shown_base[k]);
                            }
                        }
                        tracer_changed =
                            tracer_changed || slot_ordered_leaves(parse_accel_spec(text)) !=
                                                  slot_ordered_leaves(base_spec);
                        const std::string canonical = parse_accel_spec(text).canonical();
                        CHECK(parse_accel_spec(canonical).canonical() == canonical);
                        continue;
                    }
                    ++refused;
                    CHECK_THAT(why, Catch::Contains(text) && Catch::Contains("has no effect") &&
                                        Catch::Contains("'" + std::string(p.key) + "'"));
                    CHECK(why.find('\n') == std::string::npos);
                    // Refused rightly: forced past the parser, the value builds the same trees.
                    AccelSpec forced = base_spec;
                    forced.values[i] = v;
                    const std::vector<AnyAccel> f = build_all(forced, in);
                    for (std::size_t k = 0; k < in.size(); ++k) {
                        CHECK(without_settings(f[k]) == base_plain[k]);
                    }
                }
                // A key is accepted with every value or with none, and an accepted one that is
                // not build-only changes some structure.
                CHECK((refused == 0 || refused == values.size()));
                if (refused == 0) {
                    accepted.emplace_back(p.key);
                    if (p.build_only || p.tracer_only) {
                        CHECK_FALSE(changed);
                    }
                    CHECK((changed || tracer_changed) != p.build_only);
                }
            }
            // The canonical spec names exactly the keys that take effect here, and reads back.
            const std::string canonical = base_spec.canonical();
            CHECK(canonical_keys(canonical) == accepted);
            CHECK(parse_accel_spec(canonical).canonical() == canonical);
        }
    }
}

TEST_CASE("keys without effect are refused and left out of the canonical spec", "[accel][spec]") {
    for (const char* spec :
         {"bvh8,from=lbvh,ct=1,bins=2", "bvh8,from=sweep,bins=64", "bvh8,ct=1,from=lbvh",
          "bvh4,leaves=ids,leaf_align=1", "bvh:pair,from=median,block=2", "bvh8q,morton_bits=4"}) {
        CAPTURE(spec);
        CHECK_THROWS_AS(parse_accel_spec(spec), std::invalid_argument);
        CHECK_THAT(refusal(spec), Catch::Contains("has no effect"));
    }
    CHECK(refusal("bvh8,from=lbvh,ct=1") ==
          "--accel 'bvh8,from=lbvh,ct=1': 'ct' has no effect with from=lbvh (it applies with "
          "from=pbinned|binned|sweep|sbvh)");
    const std::string lbvh = parse_accel_spec("bvh8,from=lbvh").canonical();
    for (const char* key : {",ct=", ",ci=", ",bins=", ",block="}) {
        CHECK(lbvh.find(key) == std::string::npos);
    }
    CHECK(lbvh.find(",morton_bits=10") != std::string::npos);
    CHECK(parse_accel_spec("bvh8").canonical().find("morton_bits") == std::string::npos);
}

}  // namespace
}  // namespace rtlab
