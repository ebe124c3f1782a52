#pragma once
// Two kinds of failure, mapped to exit codes (docs/architecture.md, "Errors and outputs"):
//   InputError -> exit 2: bad input; the message names the file, the line/key, the value and what was expected.
//   RunError   -> exit 1: a run that failed; the message says which step and why.
#include <stdexcept>
#include <string>

namespace terracal {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace terracal
