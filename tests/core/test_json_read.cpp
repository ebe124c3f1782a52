// The JSON file reader on files that nlohmann alone would refuse without a position, or accept
// silently: other encodings, duplicate keys, numbers out of range, syntax errors with huge tokens.
// Each case: the file's bytes -> the InputError's message, which must begin with FILE:LINE:COLUMN,
// say what was found and what was expected, and stay short.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "reader_cases.hpp"

using namespace std::string_literals;
using terracal::InputError;
using terracal::test::ReaderCase;
using terracal::test::write_bytes;

namespace {

void read_all(const std::string& path) { terracal::read_json_file(path, "test file"); }

std::vector<ReaderCase> cases() {
  const std::string nested = "{\n  \"a\": 1,\n  \"b\": {\"x\": 1, \"y\": [ {\"z\": 1, \"z\": 2} ]}\n}\n";
  return {
      {"UTF-16LE with its BOM",
       "\xFF\xFE{\0\"\0a\0\"\0:\0 \0001\0}\0"s,
       ":1:1: found bytes FF FE 7B 00",
       {"byte-order mark of UTF-16LE", "expected UTF-8 text"}},
      {"UTF-16LE without BOM",
       "{\0\"\0a\0\"\0:\0 \0001\0}\0"s,
       ":1:2: found bytes 00 22 00 61",
       {"UTF-16LE text without a byte-order mark"}},
      {"UTF-32BE without BOM", "\0\0\0{\0\0\0}"s, ":1:1: found bytes 00 00 00 7B", {"UTF-32BE text without"}},
      {"Latin-1 in a string",
       "{\"a\": \"caf\xE9\"}",
       ":1:11: found bytes E9 22 7D",
       {"not valid UTF-8: Latin-1 or Windows-1252 text?", "expected UTF-8 text"}},
      {"a control character in a string", "{\"a\": \"x\x1By\"}", ":1:9: found bytes 1B 79", {"a control character"}},
      {"a NUL byte", "{\"a\": 1}\0\0"s, ":1:9: found bytes 00 00", {"a NUL byte: a binary file?"}},
      {"a duplicate key",
       "{\n  \"a\": 1,\n  \"a\": 2\n}\n",
       ":3:3: key 'a': duplicate key (first at line 2, column 3)",
       {"expected each key once in an object"}},
      {"a duplicate key deep inside", nested, ":3:33: key 'b.y[0].z': duplicate key (first at line 3, column 25)", {}},
      {"1e400",
       R"({"c": {"type": "uniform", "lower": 0, "upper": 1e400}})",
       ":1:48: key 'c.upper': '1e400' is out of range for a double",
       {"expected 0 or a number with 4.9e-324 <= |x| <= 1.8e308"}},
      {"-1e400 in an array", R"({"g": [0, 1, -1e400]})", ":1:14: key 'g[2]': '-1e400' is out of range", {}},
      {"1e-400 (rounds to 0)", "{\"g\": [0,\n 1e-400]}", ":2:2: key 'g[1]': '1e-400' is out of range", {}},
      {"a 400-digit number",
       "{\"a\": " + std::string(400, '9') + "}",
       ":1:7: key 'a': '9999999999999999999999999999999999999999'... (400 characters) is out of range",
       {}},
      {"a trailing comma",
       "{\n  \"a\": 1,\n  \"b\": 2,\n}\n",
       ":4:1: the test file is not valid JSON",
       {"syntax error while parsing object key - unexpected '}'; expected string literal"}},
      {"columns count characters",
       "{\"\xC3\xA9\": tru}",
       ":1:10: the test file is not valid JSON",
       {"invalid literal; last read: "}},
      {"an unterminated 1 MB string",
       "{\"a\": \"" + std::string(1 << 20, 'y') + "\n\"}",
       ":1:1048584: the test file is not valid JSON",
       {"must be escaped", "'... (1048585 characters)"}},
      {"an empty file", "", ":1:1: the test file is not valid JSON", {"unexpected end of input; expected '[', '{'"}},
      {"a bracket after the value",
       "{\"a\": 1}\n]",
       ":2:1: the test file is not valid JSON",
       {"unexpected ']'; expected end of input"}},
      {"a word after the value",
       "{\"a\": 1} x",
       ":1:10: the test file is not valid JSON",
       {"invalid literal; last read: '1} x'; expected end of input"}},
  };
}

}  // namespace

TEST_CASE("json read: encodings, duplicate keys, numbers out of range and syntax errors are refused clearly",
          "[core][json]") {
  const terracal::test::ScratchDir scratch("json_read");
  const std::string path = scratch.str() + "/in.json";
  terracal::test::check_refusals(cases(), path, read_all);
}

TEST_CASE("json read: a UTF-8 BOM and CRLF line endings read the same document as the plain file", "[core][json]") {
  const terracal::test::ScratchDir scratch("json_bom");
  const std::string path = scratch.str() + "/in.json";
  const std::string plain = "{\n  \"a\": 1.5,\n  \"b\": [1, 2],\n  \"c\": {\"x\": \"é\"}\n}\n";
  std::string crlf;
  for (const char c : plain) crlf += c == '\n' ? "\r\n" : std::string(1, c);
  write_bytes(path, plain);
  const nlohmann::json expected = terracal::read_json_file(path, "test file");
  CHECK(expected["c"]["x"] == "é");
  for (const std::string& bytes : {"\xEF\xBB\xBF" + plain, crlf, "\xEF\xBB\xBF" + crlf}) {
    write_bytes(path, bytes);
    CHECK(terracal::read_json_file(path, "test file") == expected);
  }
}

TEST_CASE("json read: the same key in different objects, zeros and subnormal numbers are accepted", "[core][json]") {
  const terracal::test::ScratchDir scratch("json_ok");
  const std::string path = scratch.str() + "/in.json";
  write_bytes(path,
              R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 3}, {"x": 4}], "z": [0, -0.0, 0e999, 0.0e-999, 1e-310]})");
  const nlohmann::json j = terracal::read_json_file(path, "test file");
  CHECK(j["b"]["x"] == 2);
  CHECK(j["c"][1]["x"] == 4);
  CHECK(j["z"][3].get<double>() == 0.0);
  CHECK(j["z"][4].get<double>() == 1e-310);
}

TEST_CASE("json read: a missing file names the file and the reason", "[core][json]") {
  CHECK_THROWS_WITH(terracal::read_json_file("/nonexistent/in.json", "soil file"),
                    Catch::Contains("/nonexistent/in.json: cannot open the soil file for reading"));
}
