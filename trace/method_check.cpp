// The method-list checks shared by trace, render and sweep.
#include "trace/method_check.h"

#include "base/error.h"
#include "trace/method_families.h"
#include "trace/scene_tracer.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fmt/format.h>
#include <tuple>
#include <type_traits>

namespace rtlab {

namespace {

/// Position of S in the std::tuple type List.
template <class S, class List>
struct IndexIn;
template <class S, class... Ts>
struct IndexIn<S, std::tuple<Ts...>> {
    static constexpr std::size_t value = [] {
        constexpr std::array<bool, sizeof...(Ts)> same{std::is_same_v<S, Ts>...};
        return static_cast<std::size_t>(std::find(same.begin(), same.end(), true) - same.begin());
    }();
};

void add_once(std::vector<std::string_view>& out, std::string_view family) {
    if (std::find(out.begin(), out.end(), family) == out.end()) {
        out.push_back(family);
    }
}

}  // namespace

std::vector<std::string_view> scene_families(const Scene& scene) {
    // The shapes SceneTracer gathers into its buckets (one per traced shape type), only flagged.
    std::array<bool, std::tuple_size_v<TracedShapes>> present{};
    const auto flag = [&present]<class S>(const S&, std::uint32_t) {
        static_assert(IndexIn<S, TracedShapes>::value < std::tuple_size_v<TracedShapes>,
                      "every shape a scene object emits is a traced shape type");
        present[IndexIn<S, TracedShapes>::value] = true;
    };
    for (const ObjectRef r : scene.order) {
        visit_object(scene, r, [&]<class P>(const auto& o) { P::shapes(o, 0, flag); });
    }
    std::vector<std::string_view> out;
    for_each_type<TracedShapes>([&]<class S>() {
        if (present[IndexIn<S, TracedShapes>::value]) {
            add_once(out, FamilyOf<S>::name);
        }
    });
    return out;
}

std::vector<std::string_view> tracer_families(const SceneTracer& tracer) {
    std::vector<std::string_view> out;
    for (const std::string& label : tracer.set_methods()) {
        const std::string_view family = std::string_view(label).substr(0, label.find('='));
        for (const MethodFamily& f : method_families()) {
            if (f.family == family) {
                add_once(out, f.family);  // the table's name: outlives the tracer
            }
        }
    }
    return out;
}

std::string_view method_family(std::string_view name) {
    for (const MethodFamily& f : method_families()) {
        if (std::find(f.methods.begin(), f.methods.end(), name) != f.methods.end()) {
            return f.family;
        }
    }
    return {};
}

void check_one_method_per_family(const std::vector<std::string>& methods, std::string_view what) {
    for (const MethodFamily& f : method_families()) {
        std::string first;
        for (const std::string& w : methods) {
            if (std::find(f.methods.begin(), f.methods.end(), w) == f.methods.end() || w == first) {
                continue;
            }
            if (!first.empty()) {
                throw Error(
                    fmt::format("{} names two methods of the {} family ('{}' and '{}'); give at "
                                "most one per family",
                                what, f.family, first, w));
            }
            first = w;
        }
    }
}

MethodUse method_use(std::span<const std::string_view> families,
                     const std::vector<std::string>& methods) {
    MethodUse use;
    std::vector<std::string> distinct;
    for (const std::string& w : methods) {
        if (std::find(distinct.begin(), distinct.end(), w) != distinct.end()) {
            continue;
        }
        distinct.push_back(w);
        const std::string_view family = method_family(w);
        if (std::find(families.begin(), families.end(), family) == families.end()) {
            use.unused.push_back(w);
            if (!family.empty()) {
                add_once(use.unused_families, family);
            }
        }
    }
    use.none_used = !distinct.empty() && use.unused.size() == distinct.size();
    return use;
}

}  // namespace rtlab
