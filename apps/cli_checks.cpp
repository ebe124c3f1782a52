#include "apps/cli_checks.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "apps/terrain_options.hpp"
#include "core/errors.hpp"

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

// "" when `text` is an optional sign and decimal digits naming a number in [lo, hi] (then `text`
// becomes that number in plain decimal), else the reason.
template <class T>
std::string check_whole(std::string& text, T lo, T hi) {
  const std::string outside = fmt::format("value {} is outside [{}, {}]", text, lo, hi);
  std::string digits = text;
  if (!digits.empty() && digits[0] == '+') digits.erase(0, 1);
  const bool negative = !digits.empty() && digits[0] == '-';
  if (negative) digits.erase(0, 1);
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
    return fmt::format("value {} is not a whole number in [{}, {}]", text, lo, hi);
  // The magnitude in the unsigned type, then the sign: "-0" is 0, and -2^63 still reads.
  unsigned long long magnitude = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), magnitude);
  if (ec != std::errc() || end != digits.data() + digits.size()) return outside;
  T v{};
  if (!negative) {
    if (magnitude > static_cast<unsigned long long>(std::numeric_limits<T>::max())) return outside;
    v = static_cast<T>(magnitude);
  } else if (magnitude != 0) {
    if constexpr (std::is_unsigned_v<T>) {
      return outside;
    } else {
      if (magnitude - 1 > static_cast<unsigned long long>(std::numeric_limits<T>::max())) return outside;
      v = static_cast<T>(-static_cast<T>(magnitude - 1) - 1);
    }
  }
  if (v < lo || v > hi) return outside;
  text = std::to_string(v);
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

CLI::Validator whole_in(long long lo, long long hi) {
  return CLI::Validator([lo, hi](std::string& s) { return check_whole<long long>(s, lo, hi); },
                        fmt::format("[{}, {}]", lo, hi));
}

CLI::Validator seed_value() {
  const auto hi = std::numeric_limits<std::uint64_t>::max();
  return CLI::Validator([hi](std::string& s) { return check_whole<std::uint64_t>(s, 0, hi); }, "[0, 2^64 - 1]");
}

CLI::Validator list_in_range(const Range& r) {
  const std::string expected = r.text();
  return CLI::Validator(
      [r, expected](std::string& s) -> std::string {
        try {
          for (double v : parse_list(s, "list"))
            if (!r.contains(v)) return fmt::format("value {} in the list '{}' is outside {}", v, s, expected);
        } catch (const InputError&) {
          return fmt::format("value '{}' is not a comma-separated list of numbers (expected each in {})", s, expected);
        }
        return "";
      },
      "LIST of " + expected);
}

CLI::Option* add_seed_option(CLI::App* sub, std::uint64_t& seed, const std::string& help) {
  return sub->add_option("--seed", seed, help)->transform(seed_value())->capture_default_str();
}

}  // namespace terracal::app
