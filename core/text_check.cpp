#include "core/text_check.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal {
namespace {

using namespace std::literals;

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF"sv;

struct ForeignBom {
  std::string_view bytes;
  const char* name;
};
// The UTF-32LE mark begins with the UTF-16LE one, so it is tried first.
constexpr ForeignBom kForeignBoms[] = {{"\xFF\xFE\x00\x00"sv, "UTF-32LE"},
                                       {"\x00\x00\xFE\xFF"sv, "UTF-32BE"},
                                       {"\xFF\xFE"sv, "UTF-16LE"},
                                       {"\xFE\xFF"sv, "UTF-16BE"}};

bool is_continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// "E9 2C 31 2E": up to four bytes from `offset`, what a hex viewer would show the user.
std::string hex_bytes(std::string_view bytes, std::size_t offset) {
  std::string out;
  for (std::size_t i = offset; i < bytes.size() && i < offset + 4; ++i)
    out += fmt::format("{}{:02X}", out.empty() ? "" : " ", static_cast<unsigned char>(bytes[i]));
  return out;
}

[[noreturn]] void refuse(const std::string& path, std::string_view text, std::size_t offset, std::string_view why) {
  throw InputError(fmt::format("{}: found bytes {} ({}); expected UTF-8 text", text_position(path, text, offset),
                               hex_bytes(text, offset), why));
}

void refuse_foreign_bom(const std::string& path, std::string_view bytes) {
  for (const auto& bom : kForeignBoms)
    if (bytes.starts_with(bom.bytes))
      refuse(path, bytes, 0, fmt::format("the byte-order mark of {}; save the file as UTF-8", bom.name));
}

// UTF-16 and UTF-32 text of ASCII characters has NUL bytes in a fixed pattern; anything else with
// NUL bytes is taken for a binary file.
std::string nul_diagnosis(std::string_view bytes) {
  const auto zero = [&](std::size_t i) { return i < bytes.size() && bytes[i] == '\0'; };
  if (!zero(0) && zero(1) && zero(2) && zero(3)) return "NUL bytes: UTF-32LE text without a byte-order mark?";
  if (zero(0) && zero(1) && zero(2) && !zero(3)) return "NUL bytes: UTF-32BE text without a byte-order mark?";
  if (!zero(0) && zero(1)) return "NUL bytes: UTF-16LE text without a byte-order mark?";
  if (zero(0) && !zero(1)) return "NUL bytes: UTF-16BE text without a byte-order mark?";
  return "a NUL byte: a binary file?";
}

// Length of the well-formed UTF-8 sequence that starts with the byte s[i] >= 0x80, or 0 if there is
// none. Overlong forms, UTF-16 surrogates and code points above U+10FFFF are not well-formed (RFC 3629).
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return i + k < s.size() ? static_cast<unsigned char>(s[i + k]) : 0u; };
  const unsigned lead = byte(0);
  std::size_t n = 0;
  unsigned lo = 0x80, hi = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    n = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    n = 3;
    lo = lead == 0xE0 ? 0xA0 : lo;  // overlong
    hi = lead == 0xED ? 0x9F : hi;  // surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    n = 4;
    lo = lead == 0xF0 ? 0x90 : lo;  // overlong
    hi = lead == 0xF4 ? 0x8F : hi;  // above U+10FFFF
  } else {
    return 0;
  }
  if (byte(1) < lo || byte(1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (!is_continuation(static_cast<char>(byte(k)))) return 0;
  return n;
}

// The first `keep` characters of `text`, control characters shown as \xNN, and how many there were.
struct Cut {
  std::string head;
  std::size_t chars = 0;
};
Cut cut(std::string_view text, std::size_t keep) {
  Cut c;
  std::size_t end = text.size();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (is_continuation(text[i])) continue;
    if (c.chars == keep) end = i;
    ++c.chars;
  }
  for (const char ch : text.substr(0, end)) {
    const auto u = static_cast<unsigned char>(ch);
    c.head += u < 0x20 || u == 0x7F ? fmt::format("\\x{:02X}", u) : std::string(1, ch);
  }
  return c;
}

}  // namespace

std::string read_input_bytes(const std::string& path, const std::string& what, std::size_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(fmt::format("{}: is a folder; expected the {}", path, what));
  const auto too_large = [&](const std::string& size) {
    return InputError(fmt::format("{}: the {} has {} bytes; expected at most {} bytes (is it the right file?)", path,
                                  what, size, max_bytes));
  };
  // A regular file is refused by its size before reading; a device or pipe while reading.
  if (fs::is_regular_file(path, ec)) {
    const auto size = fs::file_size(path, ec);
    if (!ec && size > max_bytes) throw too_large(std::to_string(size));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the {} for reading ({})", path, what, std::strerror(errno)));
  std::string bytes;
  std::string chunk(std::size_t{1} << 16, '\0');
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    bytes.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > max_bytes) throw too_large(fmt::format("more than {}", max_bytes));
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the {} ({})", path, what, std::strerror(errno)));
  return bytes;
}

std::string_view check_utf8_text(const std::string& path, std::string_view bytes) {
  refuse_foreign_bom(path, bytes);
  const std::string_view text = bytes.substr(bytes.starts_with(kUtf8Bom) ? kUtf8Bom.size() : 0);
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c >= 0x20 && c < 0x7F) || c == '\t' || c == '\n' || c == '\r') {
      ++i;
      continue;
    }
    if (c == 0) refuse(path, text, i, nul_diagnosis(bytes));
    if (c < 0x80) refuse(path, text, i, "a control character: a binary file?");
    const std::size_t n = utf8_sequence_length(text, i);
    if (n == 0) refuse(path, text, i, "not valid UTF-8: Latin-1 or Windows-1252 text?");
    i += n;
  }
  return text;
}

LineColumn line_column(std::string_view text, std::size_t offset) {
  const std::string_view before = text.substr(0, std::min(offset, text.size()));
  const std::size_t newline = before.rfind('\n');
  const std::string_view line = newline == std::string_view::npos ? before : before.substr(newline + 1);
  return {static_cast<std::size_t>(1 + std::count(before.begin(), before.end(), '\n')),
          static_cast<std::size_t>(
              1 + std::count_if(line.begin(), line.end(), [](char c) { return !is_continuation(c); }))};
}

std::string text_position(const std::string& path, std::string_view text, std::size_t offset) {
  const LineColumn at = line_column(text, offset);
  return fmt::format("{}:{}:{}", path, at.line, at.column);
}

std::string shorten(std::string_view text, std::size_t keep) {
  const Cut c = cut(text, keep);
  return c.chars > keep ? fmt::format("{}... ({} characters)", c.head, c.chars) : c.head;
}

std::string excerpt(std::string_view text, std::size_t keep) {
  const Cut c = cut(text, keep);
  return c.chars > keep ? fmt::format("'{}'... ({} characters)", c.head, c.chars) : fmt::format("'{}'", c.head);
}

std::string out_of_range_number(std::string_view token) {
  return fmt::format("{} is out of range for a double: expected 0 or a number with 4.9e-324 <= |x| <= 1.8e308",
                     excerpt(token));
}

}  // namespace terracal
