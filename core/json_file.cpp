#include "core/json_file.hpp"

#include <fstream>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal {

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open the {}", path, what));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range (1e400)
    throw InputError(fmt::format("{}: the {} is not valid JSON: {}", path, what, e.what()));
  }
}

}  // namespace terracal
