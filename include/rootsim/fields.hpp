#pragma once
// Field lists of the structs a run carries from one growth step to the next (the solvers' memory, the
// contact list, the rod state with its friction stick points, the run's counters): each lists its
// persistent members once, in the checkpoint's order, as
//
//   static constexpr auto fields() { return std::tuple{field("name", &S::member), ...}; }
//
// (or a FieldsOf<S> specialisation for a struct whose header should not know about it). Everything
// that copies, saves, restores, writes, reads or compares such a struct walks that list:
// Simulation::carry() and Simulation(model, state, carry) (simulation.cpp), writeCheckpoint and
// readCheckpoint (checkpoint.cpp), checkpointDifference (the tests). Adding a persistent member is
// one edit: its line in the list. A member left out of the list is scratch: not carried.
//
// Memory<S> is what a carry holds of a workspace S: a tuple of its listed fields' values (Carried<T>
// says what a field of type T carries: its value, or what its class saves, e.g. a SparseStiffness's
// SparseMemory), so that the carry mirrors no member by hand.
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace rootsim {

template <class S, class T>
struct Field {
  using Struct = S;
  using Type = T;
  const char* name;
  T S::*member;
};
template <class S, class T>
constexpr Field<S, T> field(const char* name, T S::*member) {
  return {name, member};
}

// the field list of S: S::fields(), or a specialisation of FieldsOf<S>
template <class S>
struct FieldsOf {};
template <class S>
  requires requires { S::fields(); }
struct FieldsOf<S> {
  static constexpr auto list() { return S::fields(); }
};
template <class S>
concept HasFields = requires { FieldsOf<std::remove_const_t<S>>::list(); };

// f(field) for each field of S, in order
template <class S, class F>
constexpr void forEachField(F&& f) {
  std::apply([&](const auto&... fs) { (f(fs), ...); }, FieldsOf<std::remove_const_t<S>>::list());
}
// v(name, s.member) for each field of s
template <class S, class V>
void visitFields(S& s, V&& v) {
  forEachField<S>([&](const auto& f) { v(f.name, s.*f.member); });
}

// what a field of type T carries, and how it is taken from the live value and put back (restore
// returns false when what it got does not fit; the field is then as a fresh one)
template <class T>
struct Carried {
  using type = T;
  static const T& save(const T& v) { return v; }
  static bool restore(T& to, const type& from) {
    to = from;
    return true;
  }
};

namespace detail {
template <class Tuple>
struct MemoryTuple;
template <class... F>
struct MemoryTuple<std::tuple<F...>> {
  using type = std::tuple<typename Carried<typename F::Type>::type...>;
};
template <class A, class B>
constexpr bool sameMember(A a, B b) {
  if constexpr (std::is_same_v<A, B>) return a == b;
  else return false;
}
}  // namespace detail

// what a carry holds of S: its listed fields' carried values, in the list's order
template <class S>
struct Memory {
  using Struct = S;
  typename detail::MemoryTuple<decltype(FieldsOf<S>::list())>::type values;
};

// the position of member M in S's field list (the list's size when it is not there)
template <class S, auto M>
constexpr std::size_t fieldIndex() {
  constexpr auto list = FieldsOf<S>::list();
  std::size_t index = std::tuple_size_v<decltype(list)>, i = 0;
  std::apply([&](const auto&... fs) { ((detail::sameMember(fs.member, M) ? void(index = i) : void(), ++i), ...); },
             list);
  return index;
}
// the carried value of member M: get<&NewtonWorkspace::negative>(carry.newton)
template <auto M, class S>
auto& get(Memory<S>& m) {
  constexpr std::size_t i = fieldIndex<S, M>();
  static_assert(i < std::tuple_size_v<decltype(m.values)>, "the member is not in the struct's field list");
  return std::get<i>(m.values);
}
template <auto M, class S>
const auto& get(const Memory<S>& m) {
  constexpr std::size_t i = fieldIndex<S, M>();
  static_assert(i < std::tuple_size_v<decltype(m.values)>, "the member is not in the struct's field list");
  return std::get<i>(m.values);
}

// f(field, carried value) for each field of S, in order
template <class M, class F>
void forEachCarried(M& m, F&& f) {
  using S = typename std::remove_const_t<M>::Struct;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    constexpr auto list = FieldsOf<S>::list();
    (f(std::get<I>(list), std::get<I>(m.values)), ...);
  }(std::make_index_sequence<std::tuple_size_v<decltype(m.values)>>{});
}

// f(field, value in a, value in b) for each field of S, in order
template <class S, class F>
void forEachCarried(const Memory<S>& a, const Memory<S>& b, F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    constexpr auto list = FieldsOf<S>::list();
    (f(std::get<I>(list), std::get<I>(a.values), std::get<I>(b.values)), ...);
  }(std::make_index_sequence<std::tuple_size_v<decltype(a.values)>>{});
}

// the listed fields of s (copies)
template <class S>
Memory<S> save(const S& s) {
  Memory<S> m;
  forEachCarried(m, [&](const auto& f, auto& v) {
    using T = typename std::remove_cvref_t<decltype(f)>::Type;
    v = Carried<T>::save(s.*f.member);
  });
  return m;
}
// puts them back; false when one did not fit (that one is then as a fresh one)
template <class S>
bool restore(S& s, const Memory<S>& m) {
  bool ok = true;
  forEachCarried(m, [&](const auto& f, const auto& v) {
    using T = typename std::remove_cvref_t<decltype(f)>::Type;
    ok = Carried<T>::restore(s.*f.member, v) && ok;
  });
  return ok;
}

}  // namespace rootsim
