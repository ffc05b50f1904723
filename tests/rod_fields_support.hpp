#pragma once
// Helpers for the tests that check each consumer of the rod state's field list (rod_fields.hpp) against
// every field of it: a field changed on its own, the names of the fields that differ, a state whose every
// field holds distinct values. They walk the list themselves, so a field added to it is in every test.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "rootsim/rod_fields.hpp"

namespace rootsim::test {

// the field I of the list, as a constant
template <std::size_t I>
constexpr auto rodField() {
  return std::get<I>(FieldsOf<RodState>::list());
}

// calls g(value) with each double of a field, or flag(value) with each flag
template <class T, class G, class F>
void eachValue(T& v, G&& g, F&& flag) {
  using U = std::remove_const_t<T>;
  if constexpr (std::is_same_v<U, Eigen::Matrix3Xd> || std::is_same_v<U, Eigen::VectorXd> || std::is_same_v<U, Mat3>) {
    for (Eigen::Index i = 0; i < v.size(); ++i) g(v.data()[i]);
  } else if constexpr (std::is_same_v<U, std::vector<Mat3>>) {
    for (auto& q : v)
      for (Eigen::Index i = 0; i < 9; ++i) g(q.data()[i]);
  } else if constexpr (std::is_same_v<U, std::vector<std::uint8_t>>) {
    for (auto& b : v) flag(b);
  } else {
    static_assert(std::is_same_v<U, double>, "a field type the test helpers do not know");
    g(v);
  }
}

// every value of field I changed: each double by `by`, each flag flipped
template <std::size_t I>
void perturbField(RodState& s, double by) {
  eachValue(s.*rodField<I>().member, [&](double& x) { x += by; }, [](std::uint8_t& b) { b = b ? 0 : 1; });
}

// every field given distinct values (doubles from a fixed sequence, flags alternating in a pattern that
// puts both values next to each other and two 1s in a row), the sizes as they are
inline void fillDistinct(RodState& s) {
  double x = 0.125;
  int k = 0;
  forEachRodField([&](auto index) {
    eachValue(s.*rodField<decltype(index)::value>().member, [&](double& v) { v = (x += 0.0078125); },
              [&](std::uint8_t& b) { b = (k++ % 3) != 0 ? 1 : 0; });
  });
}

// the listed fields whose values (or sizes) differ, in the list's order
inline std::vector<std::string> differingFields(const RodState& a, const RodState& b) {
  std::vector<std::string> out;
  forEachRodField([&](auto index) {
    constexpr auto f = rodField<decltype(index)::value>();
    if (valueCount(a.*f.member) != valueCount(b.*f.member)) {
      out.push_back(f.name);
      return;
    }
    std::vector<double> va, vb;
    std::vector<int> fa, fb;
    eachValue(a.*f.member, [&](double v) { va.push_back(v); }, [&](std::uint8_t v) { fa.push_back(v); });
    eachValue(b.*f.member, [&](double v) { vb.push_back(v); }, [&](std::uint8_t v) { fb.push_back(v); });
    if (va != vb || fa != fb) out.push_back(f.name);
  });
  return out;
}

}  // namespace rootsim::test
