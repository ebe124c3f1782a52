#pragma once
// CLI11 checks built from the ranges the configs define (core/range.hpp), so that an option and the
// scene or settings key it sets are checked against one definition. One check per kind of value:
// a real number in a range (in_range, off_or_in_range), a whole number (whole_in), a seed
// (seed_value), a comma list of numbers (list_in_range) and a name (add_choice).
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/range.hpp"

namespace terracal::app {

// The value lies in r.
CLI::Validator in_range(const Range& r);
// The value is 0 (the option's effect is off) or lies in r.
CLI::Validator off_or_in_range(const Range& r);
// A whole number in [lo, hi], written in decimal digits. CLI11 alone reads "-1" into an unsigned
// option as 2^64 - 1, "010" as octal 8 and "0x10" as hex 16, and refuses "1e3" or "3.5" without
// saying what it expected: this refuses anything but plain digits, naming the value and the range,
// and hands CLI11 the number in plain decimal. A transform: add it with ->transform().
CLI::Validator whole_in(long long lo, long long hi);
// A whole number that fits the option's type T, for settings whose range is checked, with a message
// of its own, where the setting is validated (--chains, --max-draws: run_calibration).
template <class T>
CLI::Validator whole_number() {
  return whole_in(std::numeric_limits<T>::min(), std::numeric_limits<T>::max());
}
// A random seed: a whole number in [0, 2^64 - 1], the range of the seeds' type (std::uint64_t).
CLI::Validator seed_value();
// A comma-separated list of numbers (as parse_list reads them), each in r.
CLI::Validator list_in_range(const Range& r);

// --seed, checked by seed_value(), its default shown: every command's seed option.
CLI::Option* add_seed_option(CLI::App* sub, std::uint64_t& seed, const std::string& help);

// An option that takes one of the names of `names` into an enum: the help shows the names and the
// default's name (never the enum's integers), and any other text is refused naming the choices.
template <class E>
CLI::Option* add_choice(CLI::App* sub, const std::string& option, E& value, const std::map<std::string, E>& names,
                        const std::string& help) {
  std::vector<std::string> keys;
  std::string current;
  for (const auto& [name, v] : names) {
    keys.push_back(name);
    if (v == value) current = name;
  }
  std::string choices;
  for (const auto& k : keys) choices += (choices.empty() ? "" : "|") + k;
  auto* opt = sub->add_option(option, value, help);
  opt->type_name(choices);
  // One transform that both refuses and maps: a name becomes the enum's number, which CLI11 then
  // reads into `value`; a number typed by the user is refused like any other unknown text.
  opt->transform(CLI::Validator(
      [names, choices](std::string& text) -> std::string {
        const auto it = names.find(text);
        if (it == names.end()) return "'" + text + "' is not one of " + choices;
        text = std::to_string(static_cast<long long>(it->second));
        return "";
      },
      "", ""));
  opt->default_str(current);
  return opt;
}

}  // namespace terracal::app
