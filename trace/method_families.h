#pragma once
// The tracer's one table of intersection-method families: a family is its name (as --method and
// `rtlab list` show it) plus the method type lists of intersect/*/methods.h, one list per shape
// type it traces. The variant of prepared sets (prim_sets.h), the name table and the factory
// below are generated from it, so a new method is one header plus one entry in its family's
// list, with no edit in trace/.

#include "intersect/box/methods.h"
#include "intersect/cone/methods.h"
#include "intersect/implicit/methods.h"
#include "intersect/method.h"
#include "intersect/polygon/methods.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab {

/// A string literal usable as a template argument (a family's name).
template <std::size_t N>
struct FixedName {
    char chars[N]{};
    /// Copies the literal, terminating zero included.
    constexpr FixedName(const char (&s)[N]) { std::copy_n(s, N, chars); }
};

/// The std::tuple of every element of the std::tuple types Lists, in order.
template <class... Lists>
using TupleCat = decltype(std::tuple_cat(std::declval<Lists>()...));

/// One method family: Name, and one method list per shape type (every list holds the same
/// methods in the same order on its own shape; the first method of a list is the default).
template <FixedName Name, class... Lists>
struct MethodFamilyEntry {
    /// The family's name, e.g. "triangle".
    static constexpr std::string_view name{Name.chars, sizeof(Name.chars) - 1};
    /// The method lists, one per shape type.
    using ShapeLists = std::tuple<Lists...>;
    /// Every method of the family over all its shape types.
    using Methods = TupleCat<Lists...>;
};

/// Every method family the tracer knows, in the order `rtlab list` shows them.
using MethodFamilyTable = std::tuple<MethodFamilyEntry<"triangle", TriangleMethods<float>>,
                                     MethodFamilyEntry<"sphere", SphereMethods<float>>,
                                     MethodFamilyEntry<"polygon", PolygonMethods<float>>,
                                     MethodFamilyEntry<"box", AabbMethods<float>>,
                                     MethodFamilyEntry<"obb", ObbMethods<float>>,
                                     MethodFamilyEntry<"implicit",
                                                       ImplicitMethods<Torus, float>,
                                                       ImplicitMethods<TangleCube, float>>,
                                     MethodFamilyEntry<"cone", ConeMethods<float>>>;

namespace detail {

template <class Table>
struct AllMethods;
template <class... Families>
struct AllMethods<std::tuple<Families...>> {
    using type = TupleCat<typename Families::Methods...>;
};

template <class List>
constexpr auto names_of(List* list = nullptr) {
    return []<class... Ms>(std::tuple<Ms...>*) {
        return std::array<std::string_view, sizeof...(Ms)>{Ms::name...};
    }(list);
}

template <class Family>
struct SameNames;
template <FixedName Name, class First, class... Lists>
struct SameNames<MethodFamilyEntry<Name, First, Lists...>>
    : std::bool_constant<((names_of<Lists>() == names_of<First>()) && ...)> {};

template <class Shape, class Family>
struct TakesShape;
template <class Shape, class... Ms>
struct TakesShape<Shape, std::tuple<Ms...>>
    : std::bool_constant<(std::is_same_v<typename Ms::Shape, Shape> || ...)> {};

template <class Shape, class Table>
struct FamilyOf;
template <class Shape, class... Families>
struct FamilyOf<Shape, std::tuple<Families...>> {
    static_assert((TakesShape<Shape, typename Families::Methods>::value + ...) == 1,
                  "exactly one method family must take each shape type");
    using type = TupleCat<std::conditional_t<TakesShape<Shape, typename Families::Methods>::value,
                                             std::tuple<Families>,
                                             std::tuple<>>...>;
};

}  // namespace detail

/// Every method of every family, in table order (the variant of prim_sets.h is built over it).
using AllFamilyMethods = typename detail::AllMethods<MethodFamilyTable>::type;

namespace detail {
template <class Table>
struct ShapeTypes;
template <class... Families>
struct ShapeTypes<std::tuple<Families...>> {
    template <class Lists>
    struct Of;
    template <class... Lists>
    struct Of<std::tuple<Lists...>> {
        using type = std::tuple<typename std::tuple_element_t<0, Lists>::Shape...>;
    };
    using type = TupleCat<typename Of<typename Families::ShapeLists>::type...>;
};
}  // namespace detail

/// Every shape type the tracer traces (one per method list), in table order: the order of a
/// scene's primitive sets.
using TracedShapes = typename detail::ShapeTypes<MethodFamilyTable>::type;

/// The family of MethodFamilyTable whose methods take Shape.
template <class Shape>
using FamilyOf = std::tuple_element_t<0, typename detail::FamilyOf<Shape, MethodFamilyTable>::type>;

/// The method names of Family, default first.
template <class Family>
std::vector<std::string_view> family_method_names() {
    static_assert(detail::SameNames<Family>::value,
                  "every shape list of a family must name the same methods in the same order");
    const auto names = detail::names_of<std::tuple_element_t<0, typename Family::ShapeLists>>();
    return {names.begin(), names.end()};
}

/// Calls f.template operator()<M>() for the method M of Shape's family that takes Shape and is
/// called `name`; returns false (calling nothing) when there is none.
template <class Shape, class F>
bool with_method_named(std::string_view name, F&& f) {
    bool found = false;
    for_each_type<typename FamilyOf<Shape>::Methods>([&]<class M>() {
        if constexpr (std::is_same_v<typename M::Shape, Shape>) {
            if (!found && M::name == name) {
                found = true;
                f.template operator()<M>();
            }
        }
    });
    return found;
}

/// The method names per primitive family, default first, as accepted by --method.
struct MethodFamily {
    std::string_view family;                ///< "triangle", "sphere", "polygon", ...
    std::vector<std::string_view> methods;  ///< method names; methods[0] is the default
};

/// Every family of MethodFamilyTable with its methods, in table order.
const std::vector<MethodFamily>& method_families();

}  // namespace rtlab
