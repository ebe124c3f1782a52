#pragma once
// Effects as modules (docs/architecture.md, "Effects"). A model's optional effects are types, each
// in a file of its own, listed once in the model's registry (an EffectList). A scene names some of
// them (an EffectSet); an effect it does not name costs nothing:
// - `with_named` turns the named effects into a compile-time list, so that the loops a scene runs
//   are compiled for exactly its effects (the CRM's neighbour loops);
// - `for_each_named` calls the named effects' hooks in registry order (host-side hooks, and models
//   whose per-node cost is too small to compile twice, such as SCM).
// Every effect type has `static constexpr const char* kName` and a `Settings` struct with a
// `static constexpr auto settings()` describing its numeric settings (core/effect_settings.hpp).
// Device code includes this header: it is C++17, with no library containers in device paths.
#include <cstddef>
#include <string>
#include <type_traits>

#include "core/host_device.hpp"

namespace terracal {

template <class... E>
struct EffectList {
  static constexpr std::size_t kSize = sizeof...(E);
};

// A marker that carries an effect type through a generic lambda without constructing it.
template <class E>
struct EffectTag {
  using type = E;
};

// Position of E in the list L (a compile error when E is not in L).
template <class E, class L>
struct EffectIndex;
template <class E, class... R>
struct EffectIndex<E, EffectList<E, R...>> : std::integral_constant<std::size_t, 0> {};
template <class E, class H, class... R>
struct EffectIndex<E, EffectList<H, R...>>
    : std::integral_constant<std::size_t, 1 + EffectIndex<E, EffectList<R...>>::value> {};

template <class E, class L>
struct EffectListHas;
template <class E, class... R>
struct EffectListHas<E, EffectList<R...>> : std::bool_constant<(std::is_same_v<E, R> || ...)> {};
template <class E, class L>
inline constexpr bool kListHas = EffectListHas<E, L>::value;

// Calls f(EffectTag<E>{}) for every E of L, in order.
template <class... E, class F>
TERRACAL_HD inline void for_each_effect(EffectList<E...>, F&& f) {
  (f(EffectTag<E>{}), ...);
}

// Which effects of the registry L a scene names, by position in L.
template <class L>
class EffectSet;
template <class... E>
class EffectSet<EffectList<E...>> {
 public:
  using List = EffectList<E...>;
  static_assert(sizeof...(E) <= 32, "an EffectSet holds at most 32 effects");

  template <class X>
  constexpr bool has() const {
    return (bits_ >> EffectIndex<X, List>::value & 1u) != 0;
  }
  template <class X>
  void set(bool on = true) {
    const unsigned bit = 1u << EffectIndex<X, List>::value;
    bits_ = on ? (bits_ | bit) : (bits_ & ~bit);
  }
  bool has_index(std::size_t i) const { return (bits_ >> i & 1u) != 0; }
  void set_index(std::size_t i, bool on = true) { bits_ = on ? (bits_ | 1u << i) : (bits_ & ~(1u << i)); }
  bool any() const { return bits_ != 0; }
  bool operator==(const EffectSet& o) const { return bits_ == o.bits_; }
  bool operator!=(const EffectSet& o) const { return bits_ != o.bits_; }

  // Calls f(EffectTag<X>{}) for each named effect X, in registry order.
  template <class F>
  void for_each_named(F&& f) const {
    ((has<E>() ? (void)f(EffectTag<E>{}) : void()), ...);
  }

  // The names of the registry, in order; the index of a name, or -1.
  static constexpr const char* kNames[sizeof...(E)] = {E::kName...};
  static int index_of(const std::string& name) {
    for (std::size_t i = 0; i < sizeof...(E); ++i)
      if (name == kNames[i]) return int(i);
    return -1;
  }

 private:
  unsigned bits_ = 0;
};

namespace detail {
template <template <class> class Pred, class Chosen, class Rest>
struct NamedDispatch;
template <template <class> class Pred, class... C>
struct NamedDispatch<Pred, EffectList<C...>, EffectList<>> {
  template <class Set, class F>
  static void run(const Set&, F&& f) {
    f(EffectList<C...>{});
  }
};
template <template <class> class Pred, class... C, class H, class... R>
struct NamedDispatch<Pred, EffectList<C...>, EffectList<H, R...>> {
  template <class Set, class F>
  static void run(const Set& set, F&& f) {
    if constexpr (Pred<H>::value) {
      if (set.template has<H>()) return NamedDispatch<Pred, EffectList<C..., H>, EffectList<R...>>::run(set, f);
    }
    NamedDispatch<Pred, EffectList<C...>, EffectList<R...>>::run(set, f);
  }
};
}  // namespace detail

// Calls f(EffectList<X...>{}) with the named effects X of the registry for which Pred<X>::value
// holds, in registry order. It instantiates f once for every subset of those effects (2^k for k
// effects that satisfy Pred): the code f compiles for a subset contains those effects and no others.
template <template <class> class Pred, class L, class F>
void with_named(const EffectSet<L>& set, F&& f) {
  detail::NamedDispatch<Pred, EffectList<>, L>::run(set, f);
}

// One value per effect of a list, reached by the effect's type: each effect's settings (host), or
// its constants or sums in the precision of the particle state (device). V<E> is the value type.
template <template <class> class V, class L>
struct PerEffect;
template <template <class> class V, class E>
struct PerEffectSlot {
  V<E> value{};
};
template <template <class> class V, class... E>
struct PerEffect<V, EffectList<E...>> : PerEffectSlot<V, E>... {
  template <class X>
  TERRACAL_HD V<X>& get() {
    return static_cast<PerEffectSlot<V, X>&>(*this).value;
  }
  template <class X>
  TERRACAL_HD const V<X>& get() const {
    return static_cast<const PerEffectSlot<V, X>&>(*this).value;
  }
};

}  // namespace terracal
