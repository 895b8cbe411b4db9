// A spec records only what takes effect: for every registry row, in every context (the defaults,
// and each value of each choice parameter), moving a key the spec accepts changes the structure
// (the same structure for a build-only key such as threads), and a key the spec refuses as having
// no effect indeed builds the same structure. The canonical spec names exactly the accepted keys.

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

/// 1000 seeded random triangles, built with exact clipping (kd-tree perfect splits) and exact
/// diagonal extents (`bounds=dop14`), so every key that can read the primitives does.
const test::Soup& soup() {
    static const test::Soup s = test::random_soup(test::SoupKind::triangles, 7, 1000);
    return s;
}

BuildInput soup_input() {
    BuildInput in = soup().input();
    in.clip = [](std::uint32_t id, const Bounds3f& box) {
        const auto& t = soup().triangles[id];
        return clip_shape_bounds(Trianglef{t.p0, t.p1, t.p2}, box);
    };
    return in;
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

/// The value a test moves parameter p to from v: the minimum, else the next integer (or the
/// maximum), the maximum for a real, the next choice for a choice.
double moved(const ParamSpec& p, double v) {
    switch (p.kind) {
    case ParamKind::integer:
        return p.min != v ? p.min : (p.min + 1 <= p.max ? p.min + 1 : p.max);
    case ParamKind::real:
        return p.min != v ? p.min : p.max;
    case ParamKind::choice:
        return v + 1 < static_cast<double>(p.choices.size()) ? v + 1 : 0;
    }
    return v;
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

/// True when the key of p changes how a structure is built but never what is built.
bool is_build_only(const ParamSpec& p) {
    return p.key == "threads";
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

TEST_CASE("every key a spec accepts takes effect, every key it refuses has none", "[accel][spec]") {
    const BuildInput in = soup_input();
    for (const AccelEntry& e : accel_registry()) {
        for (const std::string& context : contexts(e)) {
            CAPTURE(context);
            const AccelSpec base_spec = parse_accel_spec(context);
            const AnyAccel base = build_accel(base_spec, in);
            const AnyAccel base_plain = without_settings(base);
            std::vector<std::string> accepted;
            for (std::size_t i = 0; i < e.params.size(); ++i) {
                const ParamSpec& p = e.params[i];
                if (p.key == context_key(context)) {
                    accepted.emplace_back(p.key);
                    continue;
                }
                const double v = moved(p, p.default_value);
                const std::string text = with_key(context, p, v);
                CAPTURE(text);
                const std::string why = refusal(text);
                if (why.empty()) {
                    accepted.emplace_back(p.key);
                    const AnyAccel a = build_accel(text, in);
                    if (is_build_only(p)) {
                        CHECK(a == base);
                    } else {
                        CHECK_FALSE(without_settings(a) == base_plain);
                    }
                    const std::string canonical = parse_accel_spec(text).canonical();
                    CHECK(parse_accel_spec(canonical).canonical() == canonical);
                } else {
                    CHECK_THAT(why, Catch::Contains(text) && Catch::Contains("has no effect") &&
                                        Catch::Contains("'" + std::string(p.key) + "'"));
                    CHECK(why.find('\n') == std::string::npos);
                    // Refused rightly: forced past the parser, the value builds the same tree.
                    AccelSpec forced = base_spec;
                    forced.values[i] = v;
                    CHECK(without_settings(build_accel(forced, in)) == base_plain);
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
