#include "apps/cli_checks.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace terracal::app {

namespace {

// "" when `text` is a number that `accept` takes, else the reason.
template <class Accept>
std::string check_number(const std::string& text, Accept&& accept, const std::string& expected) {
  double v = 0;
  try {
    std::size_t used = 0;
    v = std::stod(text, &used);
    if (used != text.size()) return fmt::format("value {} is not a number", text);
  } catch (const std::exception&) {
    return fmt::format("value {} is not a number", text);
  }
  if (!std::isfinite(v) || !accept(v)) return fmt::format("value {} is outside {}", text, expected);
  return "";
}

}  // namespace

CLI::Validator in_range(const Range& r) {
  const std::string expected = r.text();
  return CLI::Validator(
      [r, expected](std::string& s) {
        return check_number(
            s, [&](double v) { return r.contains(v); }, expected);
      },
      expected);
}

CLI::Validator off_or_in_range(const Range& r) {
  const std::string expected = "0 (off) or " + r.text();
  return CLI::Validator(
      [r, expected](std::string& s) {
        return check_number(
            s, [&](double v) { return v == 0 || r.contains(v); }, expected);
      },
      expected);
}

}  // namespace terracal::app
