#pragma once
// The effects' names and settings as every model reads, checks and records them, written once over
// an effect registry (core/effect_list.hpp) and the settings() of each effect (core/setting.hpp):
// - read_effects: a config's "effects" list and each named effect's settings object;
// - check_effect_settings: the same checks on values that code built;
// - effects_text: a canonical text of the named effects and their settings, for cache keys.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/effect_list.hpp"
#include "core/errors.hpp"
#include "core/json_object.hpp"
#include "core/setting.hpp"

namespace terracal {

template <class E>
using EffectSettingsOf = typename E::Settings;

// What a scene names of a registry L, and the settings of every effect of L (the defaults where an
// effect is not named).
template <class L>
struct EffectChoice {
  EffectSet<L> named;
  PerEffect<EffectSettingsOf, L> settings;

  template <class E>
  bool on() const {
    return named.template has<E>();
  }
  template <class E>
  const typename E::Settings& of() const {
    return settings.template get<E>();
  }
  template <class E>
  void enable(const typename E::Settings& s = {}) {
    named.template set<E>();
    settings.template get<E>() = s;
  }
  template <class E>
  void disable() {
    named.template set<E>(false);
    settings.template get<E>() = {};
  }
};

// Throws InputError naming `key` and the unknown name, listing the known ones.
template <class L>
EffectSet<L> effect_set_from_names(const std::vector<std::string>& names, const std::string& key) {
  EffectSet<L> set;
  for (const auto& n : names) {
    const int i = EffectSet<L>::index_of(n);
    if (i < 0) {
      std::string known;
      for (const char* k : EffectSet<L>::kNames) known += (known.empty() ? "" : ", ") + std::string(k);
      throw InputError(fmt::format("{}: unknown effect '{}'; known: {}", key, n, known));
    }
    set.set_index(std::size_t(i));
  }
  return set;
}

template <class L>
std::vector<std::string> effect_names(const EffectSet<L>& set) {
  std::vector<std::string> out;
  set.for_each_named([&](auto tag) { out.push_back(decltype(tag)::type::kName); });
  return out;
}

// Reads o["effects"] (names of L) and, for every effect of L, its settings object o[name]: allowed
// only for a named effect, each key checked against its Range, unknown keys refused.
template <class L>
EffectChoice<L> read_effects(JsonObject& o) {
  EffectChoice<L> c;
  std::vector<std::string> allowed(std::begin(EffectSet<L>::kNames), std::end(EffectSet<L>::kNames));
  c.named = effect_set_from_names<L>(o.strings_or("effects", allowed), o.key_path("effects"));
  for_each_effect(L{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    if (!o.has(E::kName)) return;
    if (!c.named.template has<E>())
      o.fail(E::kName, fmt::format("settings given, but \"{}\" is not named in 'effects'", E::kName));
    JsonObject s = o.object(E::kName);
    typename E::Settings& v = c.settings.template get<E>();
    for (const auto& spec : E::settings())
      if (s.has(spec.key)) spec.put(v, s.number(spec.key, spec.range, spec.whole != nullptr));
    s.finish();
  });
  return c;
}

// Checks every named effect's settings against their ranges; errors name "<effect>.<key>".
template <class L>
void check_effect_settings(const EffectChoice<L>& c, const std::string& where) {
  c.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    for (const auto& spec : E::settings())
      check_range(spec.range, spec.get(c.template of<E>()), fmt::format("{}.{}", E::kName, spec.key), where);
  });
}

// "name{key=value,...} name ..." over the named effects: equal texts, equal effects.
template <class L>
std::string effects_text(const EffectChoice<L>& c) {
  std::string out;
  c.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    out += fmt::format("{}{}{{", out.empty() ? "" : " ", E::kName);
    bool first = true;
    for (const auto& spec : E::settings()) {
      out += fmt::format("{}{}={}", first ? "" : ",", spec.key, spec.get(c.template of<E>()));
      first = false;
    }
    out += "}";
  });
  return out;
}

}  // namespace terracal
