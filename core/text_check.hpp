#pragma once
// The checks and message pieces that every text input reader shares (CSV in core/csv.cpp, JSON in
// core/json_file.cpp), so both refuse the same files with the same words:
//   - input files are UTF-8 text: an optional UTF-8 byte-order mark, then no NUL bytes, no control
//     characters other than tab, CR and LF, and only well-formed UTF-8 sequences;
//   - what a message quotes from a file is shortened, never dumped whole;
//   - positions are "FILE:LINE:COLUMN", 1-based, the column counted in characters.
// Every refusal is an InputError (exit code 2).
#include <cstddef>
#include <string>
#include <string_view>

namespace terracal {

// Larger input files are refused before they are read: the curve and config files are a few MB at
// most, and the limit keeps a wrongly chosen file (a disk image, /dev/zero) from taking minutes.
inline constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;

// The bytes of the file at `path`. Throws InputError naming the file and `what` it was meant to be
// ("file", "priors file") when it cannot be opened, is a folder, or has more than `max_bytes`.
std::string read_input_bytes(const std::string& path, const std::string& what, std::size_t max_bytes = kMaxInputBytes);

// Returns the text after an optional UTF-8 byte-order mark. Throws InputError
// "PATH:LINE:COLUMN: found ...; expected UTF-8 text" for a UTF-16 or UTF-32 file (with or without
// its byte-order mark), bytes that are not UTF-8 (Latin-1, Windows-1252) and binary data.
std::string_view check_utf8_text(const std::string& path, std::string_view bytes);

// Line and column (1-based, the column counted in characters) of byte `offset` of `text`, which is
// UTF-8 as check_utf8_text returns it (the byte-order mark removed).
struct LineColumn {
  std::size_t line = 1, column = 1;
};
LineColumn line_column(std::string_view text, std::size_t offset);
// "PATH:LINE:COLUMN" of byte `offset` of `text`.
std::string text_position(const std::string& path, std::string_view text, std::size_t offset);

// TEXT when it has at most `keep` characters, else ITS FIRST `keep` CHARACTERS... (N characters).
// Control characters are shown as \xNN so that a message stays on one line.
std::string shorten(std::string_view text, std::size_t keep = 40);
// The same in single quotes: 'TEXT', or 'ITS FIRST `keep` CHARACTERS'... (N characters).
std::string excerpt(std::string_view text, std::size_t keep = 40);

// "'TOKEN' is out of range for a double: expected ..." for a number that overflows (1e309) or is
// non-zero but rounds to zero (1e-400). Subnormal values (1e-310) are kept as they are.
std::string out_of_range_number(std::string_view token);

}  // namespace terracal
