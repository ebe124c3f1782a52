#pragma once
// The table form that the reader tests share: a file's bytes -> the InputError's message, which must
// begin with FILE plus `where` (":LINE[:COLUMN]..."), contain every phrase, and stay short.
#include <catch2/catch.hpp>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace terracal::test {

struct ReaderCase {
  const char* name;
  std::string bytes;
  std::string where;  // what follows the file's path at the start of the message
  std::vector<std::string> phrases;
};

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The message of the InputError that `read` throws for the file at `path`; "" when it throws none.
inline std::string input_error_of(const std::function<void(const std::string&)>& read, const std::string& path) {
  try {
    read(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Writes each case's bytes to `path`, reads it with `read` and checks the message.
inline void check_refusals(const std::vector<ReaderCase>& cases, const std::string& path,
                           const std::function<void(const std::string&)>& read) {
  for (const auto& c : cases) {
    SECTION(c.name) {
      write_bytes(path, c.bytes);
      const std::string message = input_error_of(read, path);
      INFO(c.name << ": the message was: " << message);
      CHECK(message.find(path + c.where) == 0);
      for (const auto& p : c.phrases) CHECK(message.find(p) != std::string::npos);
      CHECK(message.size() < path.size() + 250);  // what was found is shortened, never dumped
    }
  }
}

}  // namespace terracal::test
