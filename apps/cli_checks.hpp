#pragma once
// CLI11 checks built from the ranges the configs define (core/range.hpp), so that an option and the
// scene or settings key it sets are checked against one definition.
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
