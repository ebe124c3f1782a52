#pragma once
// Reads a JSON input file. Cannot open or not JSON: InputError naming the file, what it was meant
// to be (`what`, e.g. "priors file") and the parser's message with its position.
#include <string>

#include <nlohmann/json.hpp>

namespace terracal {

nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace terracal
