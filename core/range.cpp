#include "core/range.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"

namespace terracal {

std::string Range::text() const {
  std::string s = fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  if (unit && *unit) s += fmt::format(" {}", unit);
  return s;
}

void check_range(const Range& r, double v, const std::string& key, const std::string& where) {
  if (r.contains(v)) return;
  const std::string prefix = where.empty() ? "" : where + ": ";
  throw InputError(fmt::format("{}key '{}': value {} is outside the allowed range {}", prefix, key, v, r.text()));
}

void check_distinct(const std::vector<double>& values, const std::string& key, const std::string& why) {
  for (auto it = values.begin(); it != values.end(); ++it)
    if (std::find(values.begin(), it, *it) != it)
      throw InputError(fmt::format("{} {}: the value {} is given twice; {}", key, fmt::join(values, ","), *it, why));
}

}  // namespace terracal
