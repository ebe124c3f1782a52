#pragma once
// CLI11 checks built from the ranges the configs define (core/range.hpp), so that an option and the
// scene or settings key it sets are checked against one definition.
#include <CLI/CLI.hpp>

#include "core/range.hpp"

namespace terracal::app {

// The value lies in r.
CLI::Validator in_range(const Range& r);
// The value is 0 (the option's effect is off) or lies in r.
CLI::Validator off_or_in_range(const Range& r);

}  // namespace terracal::app
