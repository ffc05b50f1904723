#pragma once
// The rod state's field list (RodState, rod.hpp): its persistent members once, each with where it lives
// and how splitting an element treats it, in the checkpoint's order. Apart from rod.hpp so that only the
// files that walk the list include it.
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "rootsim/fields.hpp"
#include "rootsim/rod.hpp"

namespace rootsim {

// What each consumer of the rod state's field list needs to know of a field, so that none of them
// names a field by hand: resize, splitLongElements, the checkpoint (write, read, element-count check,
// difference) and Python's State walk the list below.
//
// where a field lives: one value per node (n+1), element (n), Voronoi domain (n-1), or one for the rod
enum class Along { Node, Element, Voronoi, Rod };
// what splitting an element in two does to it (splitLongElements): kept nodes, elements and Voronoi
// domains keep their values; a new node, the two halves and the new Voronoi domain inside the split
// element take
enum class OnSplit {
  Mean,       // the mean of the two neighbours (a node's of the element's two nodes, a Voronoi
              // domain's of the neighbouring domains; an end domain's of its one neighbour)
  Both,       // a flag: 1 when both of the element's nodes have it
  Copy,       // the element's value in both halves; a whole-rod value as it was
  Halve,      // half the element's value each (rest lengths)
  Zero,       // every value 0 after a split (velocities: the split state starts at rest)
  Recompute,  // left for splitLongElements to recompute from the other fields (material coordinates)
};
// the unit Python's State gives the field (the run directory's files' units): SI divided by units::mm
// (Length, per unit time too), by units::hour (Time), times units::mm (Curvature), or as is (None)
enum class Unit { None, Length, Time, Curvature };

template <class T>
struct RodField : Field<RodState, T> {
  Along along;
  OnSplit split;
  const char* python;  // its name in Python's State, its unit in the name
  Unit unit;
};
template <class T>
constexpr RodField<T> rodField(const char* name, T RodState::*member, Along along, OnSplit split, const char* python,
                               Unit unit) {
  return {{name, member}, along, split, python, unit};
}

// the rod state's field list, in the checkpoint's order: all of it persists (the friction stick points
// included). A field added to RodState is added here, once.
template <>
struct FieldsOf<RodState> {
  static constexpr auto list() {
    using R = RodState;
    using A = Along;
    using P = OnSplit;
    return std::tuple{
        rodField("x", &R::x, A::Node, P::Mean, "positions_mm", Unit::Length),
        rodField("v", &R::v, A::Node, P::Zero, "velocities_mm_per_s", Unit::Length),
        rodField("Q", &R::Q, A::Element, P::Copy, "directors", Unit::None),
        rodField("w", &R::w, A::Element, P::Zero, "angular_velocities_rad_per_s", Unit::None),
        rodField("l0", &R::l0, A::Element, P::Halve, "rest_lengths_mm", Unit::Length),
        rodField("S", &R::S, A::Node, P::Recompute, "s_mm", Unit::Length),
        rodField("kappa0", &R::kappa0, A::Voronoi, P::Mean, "kappa0_vector_per_mm", Unit::Curvature),
        rodField("anchor", &R::anchor, A::Node, P::Mean, "anchors_mm", Unit::Length),
        rodField("anchored", &R::anchored, A::Node, P::Both, "anchored", Unit::None),
        rodField("plateStick", &R::plateStick, A::Node, P::Mean, "plate_sticks_mm", Unit::Length),
        rodField("hasPlateStick", &R::hasPlateStick, A::Node, P::Both, "has_plate_stick", Unit::None),
        rodField("obstacleStick", &R::obstacleStick, A::Node, P::Mean, "obstacle_sticks_mm", Unit::Length),
        rodField("hasObstacleStick", &R::hasObstacleStick, A::Node, P::Both, "has_obstacle_stick", Unit::None),
        rodField("clampFrame", &R::clampFrame, A::Rod, P::Copy, "clamp_frame", Unit::None),
        rodField("time", &R::time, A::Rod, P::Copy, "time_h", Unit::Time)};
  }
};

// every member of RodState is listed: the listed members' sizes add up to the struct's (its members are
// all 8-byte aligned, so it has no padding), so a member added to RodState and not here stops the build
constexpr std::size_t listedRodStateBytes() {
  return std::apply([](const auto&... f) { return (sizeof(typename std::remove_cvref_t<decltype(f)>::Type) + ...); },
                    FieldsOf<RodState>::list());
}
static_assert(listedRodStateBytes() == sizeof(RodState),
              "a member of RodState is missing from its field list (rod_fields.hpp), or one is listed twice");

// the number of values a field along `a` has on a rod of n elements (Rod: 1)
constexpr int valuesAlong(Along a, int n) {
  return a == Along::Node ? n + 1 : a == Along::Element ? n : a == Along::Voronoi ? (n > 1 ? n - 1 : 0) : 1;
}
// the number of values (columns, entries) a field holds (1 for a single value)
template <class T>
long valueCount(const T& v) {
  if constexpr (std::is_same_v<T, Eigen::Matrix3Xd>) return static_cast<long>(v.cols());
  else if constexpr (std::is_same_v<T, Eigen::VectorXd>) return static_cast<long>(v.size());
  else if constexpr (std::is_same_v<T, Mat3> || std::is_arithmetic_v<T>) return 1;
  else return static_cast<long>(v.size());  // a std::vector
}
// f(std::integral_constant<std::size_t, I>{}) for each field index I of the list, in order: f reads
// field I as a constant (std::get<decltype(I)::value>(FieldsOf<RodState>::list())) and may choose by it
// with if constexpr
template <class F>
constexpr void forEachRodField(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) { (f(std::integral_constant<std::size_t, I>{}), ...); }(
      std::make_index_sequence<std::tuple_size_v<decltype(FieldsOf<RodState>::list())>>{});
}

// the first listed field whose length disagrees with the rest lengths' element count (nullptr: none)
const char* fieldOffElementCount(const RodState& s);

}  // namespace rootsim
