#pragma once
// One numeric setting of an effect, described once: its key (under the effect's name in a scene),
// the member of the effect's Settings struct it fills, its allowed range and a sentence of help.
// Its default is the member's initialiser in that struct, so each default exists in one place.
// The readers, validators, fingerprints and command-line options of every model work from these
// descriptions (core/effect_settings.hpp); an effect declares them in
//   static constexpr auto settings() { return std::array{real_setting(...), ...}; }
#include <array>

#include "core/range.hpp"

namespace terracal {

template <class S>
struct Setting {
  const char* key;
  double S::*real = nullptr;  // exactly one of the two members is set
  int S::*whole = nullptr;
  Range range;
  const char* help;

  double get(const S& s) const { return real ? s.*real : double(s.*whole); }
  void put(S& s, double v) const {
    if (real)
      s.*real = v;
    else
      s.*whole = int(v);
  }
};

template <class S>
constexpr Setting<S> real_setting(const char* key, double S::*field, Range range, const char* help) {
  return {key, field, nullptr, range, help};
}
template <class S>
constexpr Setting<S> whole_setting(const char* key, int S::*field, Range range, const char* help) {
  return {key, nullptr, field, range, help};
}

// The settings() of an effect that has none.
template <class S>
constexpr std::array<Setting<S>, 0> no_settings() {
  return {};
}

}  // namespace terracal
