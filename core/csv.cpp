#include "core/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"

namespace terracal {
namespace {

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
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
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open the file for reading", path));
  CsvTable t;
  t.path_ = path;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    if (t.header_.empty()) {
      t.header_ = split(s);
      t.header_line_ = line_no;
      continue;
    }
    t.cells_.push_back(split(s));
    t.lines_.push_back(line_no);
    if (t.cells_.back().size() > t.header_.size())
      throw InputError(fmt::format("{}:{}: {} cells but the header has {} columns ({})", path, line_no,
                                   t.cells_.back().size(), t.header_.size(), fmt::join(t.header_, ",")));
  }
  if (t.header_.empty())
    throw InputError(fmt::format("{}: the file is empty (expected a header row and data rows)", path));
  if (t.cells_.empty())
    throw InputError(fmt::format("{}: the file has a header ({}) but no data rows", path, fmt::join(t.header_, ",")));
  return t;
}

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
    throw InputError(fmt::format("{}:{}: missing column(s) {}; the header is '{}', expected the columns {}", path_,
                                 header_line_, fmt::join(missing, ", "), fmt::join(header_, ","),
                                 fmt::join(names, ",")));
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
  if (ec != std::errc() || ptr != s.data() + s.size())
    throw InputError(fmt::format("{}: '{}' is not a number", where(row, column), s));
  if (!std::isfinite(v)) throw InputError(fmt::format("{}: '{}' is not a finite number", where(row, column), s));
  return v;
}

double CsvTable::number(std::size_t row, const std::string& column) const {
  const auto v = optional_number(row, column);
  if (!v) throw InputError(fmt::format("{}: the cell is empty; expected a number", where(row, column)));
  return *v;
}

}  // namespace terracal
