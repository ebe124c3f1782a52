// The CSV reader on files that are not plain ASCII: other encodings, binary data, numbers out of
// range, huge cells and lines. Each case: the file's bytes -> the InputError's message, which must
// name the file and the line (and column), say what was found and stay short.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "core/csv.hpp"
#include "core/errors.hpp"
#include "core/text_check.hpp"
#include "reader_cases.hpp"

using namespace std::string_literals;
using terracal::CsvTable;
using terracal::InputError;
using terracal::test::ReaderCase;
using terracal::test::write_bytes;

namespace {

const std::string kPlain = "a,b\n0.1,2\n0.2,3\n";

// The file as text in another encoding; `plain` is ASCII, so each byte becomes one code unit.
std::string utf16(const std::string& plain, bool big_endian) {
  std::string out;
  for (const char c : plain) out += big_endian ? "\0"s + c : c + "\0"s;
  return out;
}
std::string utf32(const std::string& plain, bool big_endian) {
  std::string out;
  for (const char c : plain) out += big_endian ? "\0\0\0"s + c : c + "\0\0\0"s;
  return out;
}

// Reads the table and every number in it.
void read_all(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  for (std::size_t r = 0; r < t.rows(); ++r) t.number(r, "a"), t.number(r, "b");
}

// Built once: each SECTION runs the test case again, and the big cases are 110 MB together.
const std::vector<ReaderCase>& cases() {
  static const std::vector<ReaderCase> all = {
      {"UTF-16LE with its BOM",
       "\xFF\xFE"s + utf16(kPlain, false),
       ":1:1: found bytes FF FE 61 00",
       {"byte-order mark of UTF-16LE", "expected UTF-8 text"}},
      {"UTF-16BE with its BOM",
       "\xFE\xFF"s + utf16(kPlain, true),
       ":1:1: found bytes FE FF 00 61",
       {"byte-order mark of UTF-16BE", "expected UTF-8 text"}},
      {"UTF-32LE with its BOM",
       "\xFF\xFE\0\0"s + utf32(kPlain, false),
       ":1:1: found bytes FF FE 00 00",
       {"byte-order mark of UTF-32LE"}},
      {"UTF-32BE with its BOM",
       "\0\0\xFE\xFF"s + utf32(kPlain, true),
       ":1:1: found bytes 00 00 FE FF",
       {"byte-order mark of UTF-32BE"}},
      {"UTF-16LE without BOM",
       utf16(kPlain, false),
       ":1:2: found bytes 00 2C 00 62",
       {"UTF-16LE text without a byte-order mark", "expected UTF-8 text"}},
      {"UTF-16BE without BOM", utf16(kPlain, true), ":1:1: found bytes 00 61", {"UTF-16BE text without"}},
      {"UTF-32LE without BOM", utf32(kPlain, false), ":1:2: found bytes 00 00 00 2C", {"UTF-32LE text without"}},
      {"Latin-1 in a comment",
       "a,b\n# caf\xE9 au lait\n0.1,2\n",
       ":2:6: found bytes E9 20 61 75",
       {"not valid UTF-8: Latin-1 or Windows-1252 text?", "expected UTF-8 text"}},
      {"Latin-1 in the header", "temp\xE9rature,a,b\n1,0.1,2\n", ":1:5: found bytes E9 72 61 74", {"not valid UTF-8"}},
      {"UTF-8 of a surrogate", "a,b\n0.1,\xED\xA0\x80\n", ":2:5: found bytes ED A0 80", {"not valid UTF-8"}},
      {"overlong UTF-8", "a,b\n0.1,\xC0\xAE\n", ":2:5: found bytes C0 AE", {"not valid UTF-8"}},
      {"UTF-8 cut at the end", "a,b\n0.1,2\xC3", ":2:6: found bytes C3", {"not valid UTF-8"}},
      {"a control character", "a,b\n0.1,2\n0.2,\x01\n", ":3:5: found bytes 01 0A", {"a control character"}},
      {"a NUL byte in a row", "a,b\n0.1,2\0\n"s, ":2:6: found bytes 00 0A", {"a NUL byte: a binary file?"}},
      {"a binary file",
       "\x7F"
       "ELF\x02\x01\x01\0\0\0"s,
       ":1:1: found bytes 7F 45 4C 46",
       {"a control character"}},
      {"1e309",
       "a,b\n0.1,2\n0.2,1e309\n",
       ":3, column 'b' (2): '1e309' is out of range for a double",
       {"expected 0 or a number with 4.9e-324 <= |x| <= 1.8e308"}},
      {"-1e309", "a,b\n-1e309,2\n", ":2, column 'a' (1): '-1e309' is out of range for a double", {}},
      {"1e-400 (rounds to 0)", "a,b\n0.1,1e-400\n", ":2, column 'b' (2): '1e-400' is out of range for a double", {}},
      {"not a number", "a,b\n0.1,abc\n", ":2, column 'b' (2): 'abc' is not a number", {"expected a decimal number"}},
      {"a 30000-character cell",
       "a,b\n0.1," + std::string(30000, 'x') + "\n",
       ":2, column 'b' (2): 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx'... (30000 characters) is not a number",
       {}},
      {"a 10 MB cell",
       "a,b\n0.1," + std::string(10 << 20, '7') + "\n",
       ":2: the line is longer than 65536 bytes: found '0.1,777",
       {"'... (10485764 characters); expected a row of short cells"}},
      {"a 100 MB single line",
       std::string(100 << 20, '1'),
       ":1: the line is longer than 65536 bytes: found '1111",
       {"'... (104857600 characters)"}},
      {"nothing but a UTF-8 BOM", "\xEF\xBB\xBF", ": the file is empty", {}},
  };
  return all;
}

}  // namespace

TEST_CASE("csv read: other encodings, binary data, out-of-range numbers and huge lines are refused clearly",
          "[core][csv]") {
  const terracal::test::ScratchDir scratch("csv_read");
  const std::string path = scratch.str() + "/plate.csv";
  terracal::test::check_refusals(cases(), path, read_all);
}

TEST_CASE("csv read: a UTF-8 BOM and CRLF line endings read the same values as the plain file", "[core][csv]") {
  const terracal::test::ScratchDir scratch("csv_bom");
  const std::string path = scratch.str() + "/plate.csv";
  std::string crlf;
  for (const char c : "# température, °C\n" + kPlain) crlf += c == '\n' ? "\r\n" : std::string(1, c);
  for (const std::string& bytes : {kPlain, "\xEF\xBB\xBF" + kPlain, crlf, "\xEF\xBB\xBF" + crlf}) {
    write_bytes(path, bytes);
    const CsvTable t = CsvTable::read(path);
    REQUIRE(t.has_column("a"));  // the BOM is not part of the first column's name
    REQUIRE(t.rows() == 2);
    CHECK(t.number(0, "a") == 0.1);
    CHECK(t.number(1, "b") == 3.0);
    CHECK(t.text(1, "b") == "3");  // no CR left on the last cell
  }
}

TEST_CASE("csv read: subnormal numbers are kept, numbers that round to 0 are refused", "[core][csv]") {
  const terracal::test::ScratchDir scratch("csv_subnormal");
  const std::string path = scratch.str() + "/plate.csv";
  write_bytes(path, "a,b\n1e-310,0e-999\n");
  const CsvTable t = CsvTable::read(path);
  CHECK(t.number(0, "a") == 1e-310);
  CHECK(t.number(0, "b") == 0.0);
  write_bytes(path, "a,b\n1e-330,0\n");
  CHECK_THROWS_WITH(CsvTable::read(path).number(0, "a"), Catch::Contains("'1e-330' is out of range for a double"));
}

TEST_CASE("input files: a folder, a missing file and a file over the size limit are refused", "[core][csv]") {
  const terracal::test::ScratchDir scratch("csv_limits");
  const std::string dir = scratch.str();
  CHECK_THROWS_WITH(CsvTable::read(dir), Catch::Contains(dir + ": is a folder; expected the file"));
  CHECK_THROWS_WITH(CsvTable::read(dir + "/none.csv"),
                    Catch::Contains(dir + "/none.csv: cannot open the file for reading (No such file or directory)"));
  write_bytes(dir + "/big.csv", std::string(2048, '1'));
  CHECK_THROWS_WITH(terracal::read_input_bytes(dir + "/big.csv", "file", 1024),
                    Catch::Contains(dir + "/big.csv: the file has 2048 bytes; expected at most 1024 bytes"));
  CHECK(terracal::read_input_bytes(dir + "/big.csv", "file", 2048).size() == 2048);
}
