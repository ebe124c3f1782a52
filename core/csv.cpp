#include "core/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal {
namespace {

// Curve rows are a few dozen characters. A much longer line is not a curve row (a binary or
// minified file, a paste gone wrong); refusing it at once also keeps every message that quotes the
// header or a cell short.
constexpr std::size_t kMaxLineBytes = 64 * 1024;

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

CsvTable CsvTable::read(const std::string& path) {
  const std::string bytes = read_input_bytes(path, "file");
  // A UTF-8 byte-order mark is dropped here, so it never sticks to the first column's name.
  const std::string_view text = check_utf8_text(path, bytes);
  CsvTable t;
  t.path_ = path;
  int line_no = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    t.add_line(text.substr(start, end - start), ++line_no);
    start = end + 1;
  }
  if (t.header_.empty())
    throw InputError(fmt::format("{}: the file is empty (expected a header row and data rows)", path));
  if (t.cells_.empty())
    throw InputError(fmt::format("{}: the file has a header ({}) but no data rows", path, t.header_text()));
  return t;
}

void CsvTable::add_line(std::string_view line, int line_no) {
  if (line.size() > kMaxLineBytes)
    throw InputError(fmt::format("{}:{}: the line is longer than {} bytes: found {}; expected a row of short cells",
                                 path_, line_no, kMaxLineBytes, excerpt(line)));
  const std::string s = trim(line);  // a CR of a CRLF line ending goes here
  if (s.empty() || s[0] == '#') return;
  if (header_.empty()) {
    header_ = split(s);
    header_line_ = line_no;
    return;
  }
  cells_.push_back(split(s));
  lines_.push_back(line_no);
  if (cells_.back().size() > header_.size())
    throw InputError(fmt::format("{}:{}: {} cells but the header has {} columns ({})", path_, line_no,
                                 cells_.back().size(), header_.size(), header_text()));
}

std::string CsvTable::header_text() const { return excerpt(fmt::format("{}", fmt::join(header_, ","))); }

int CsvTable::column_index(const std::string& name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return static_cast<int>(i);
  return -1;
}

void CsvTable::require_columns(const std::vector<std::string>& names) const {
  std::vector<std::string> missing;
  for (const auto& n : names)
    if (!has_column(n)) missing.push_back(n);
  if (!missing.empty())
    throw InputError(fmt::format("{}:{}: missing column(s) {}; the header is {}, expected the columns {}", path_,
                                 header_line_, fmt::join(missing, ", "), header_text(), fmt::join(names, ",")));
}

std::string CsvTable::where(std::size_t row, const std::string& column) const {
  return fmt::format("{}:{}, column '{}' ({})", path_, lines_[row], column, column_index(column) + 1);
}

std::string CsvTable::text(std::size_t row, const std::string& column) const {
  const int c = column_index(column);
  if (c < 0 || static_cast<std::size_t>(c) >= cells_[row].size()) return "";
  return cells_[row][c];
}

std::optional<double> CsvTable::optional_number(std::size_t row, const std::string& column) const {
  const std::string s = text(row, column);
  if (s.empty()) return std::nullopt;
  double v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ptr != s.data() + s.size() || ec == std::errc::invalid_argument)
    throw InputError(fmt::format("{}: {} is not a number; expected a decimal number such as 0.0125 or 1.5e3",
                                 where(row, column), excerpt(s)));
  // from_chars leaves v alone for 1e309 and also for 1e-400, which would round to 0: both are refused.
  if (ec == std::errc::result_out_of_range)
    throw InputError(fmt::format("{}: {}", where(row, column), out_of_range_number(s)));
  if (!std::isfinite(v))
    throw InputError(fmt::format("{}: {} is not a finite number; expected a decimal number such as 0.0125 or 1.5e3",
                                 where(row, column), excerpt(s)));
  return v;
}

double CsvTable::number(std::size_t row, const std::string& column) const {
  const auto v = optional_number(row, column);
  if (!v) throw InputError(fmt::format("{}: the cell is empty; expected a number", where(row, column)));
  return *v;
}

}  // namespace terracal
