#pragma once
// Reads a JSON input file. Throws InputError naming the file, what it was meant to be (`what`, e.g.
// "priors file") and LINE:COLUMN when it cannot be opened, is not UTF-8 text (core/text_check.hpp;
// a UTF-8 byte-order mark and CRLF line endings are fine), is not JSON, has a key twice in one
// object, or has a number out of range for a double (1e400, or 1e-400 that would round to 0).
#include <string>

#include <nlohmann/json.hpp>

namespace terracal {

nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace terracal
