#pragma once
// The allowed values of one numeric setting, defined once and checked everywhere the setting
// arrives: the scene and config readers (JsonObject::number), the command line (a CLI11 check,
// apps/cli_checks.hpp) and values that code builds (validate_* functions). One definition, so that
// the three can never disagree (docs/architecture.md, "Settings").
#include <string>
#include <vector>

namespace terracal {

struct Range {
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;
  const char* unit = "";  // SI unit for messages, "" for a plain number

  // NaN is never inside.
  constexpr bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  // "(0, 2]" with the unit after it: "(0, 2] m".
  std::string text() const;
};

// Throws InputError "<where>key 'KEY': value V is outside the allowed range R" unless r holds v.
// `where` is a file name (or empty for a command-line option, whose name is the key).
void check_range(const Range& r, double v, const std::string& key, const std::string& where = "");

// Throws InputError "KEY A,B,A: the value A is given twice; WHY" for lists whose values name things
// (plate radii key the curves of plate.csv: two plates of one radius would read as one curve).
void check_distinct(const std::vector<double>& values, const std::string& key, const std::string& why);

}  // namespace terracal
