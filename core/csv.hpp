#pragma once
// A small CSV reader for the curve files: a required header row, '#' comment lines, numeric
// cells. Every error names the file, the line, the column and what was expected, so a user can
// go straight to the cell (InputError, exit code 2). The file must be UTF-8 text (an optional
// byte-order mark, LF or CRLF line endings; core/text_check.hpp); lines are at most 64 KiB.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace terracal {

class CsvTable {
 public:
  // Reads the whole file. Throws InputError if it cannot be opened, is empty or has no header.
  static CsvTable read(const std::string& path);

  const std::string& path() const { return path_; }
  std::size_t rows() const { return cells_.size(); }
  int line_of(std::size_t row) const { return lines_[row]; }
  bool has_column(const std::string& name) const { return column_index(name) >= 0; }
  int column_index(const std::string& name) const;

  // Throws InputError naming every missing column (and listing the header that was found).
  void require_columns(const std::vector<std::string>& names) const;

  // A numeric cell. Throws InputError for an empty, non-numeric, NaN or infinite cell, and for a
  // number out of range for a double (1e309, or 1e-400 that would round to 0).
  double number(std::size_t row, const std::string& column) const;
  // As number(), but an empty cell gives nullopt.
  std::optional<double> optional_number(std::size_t row, const std::string& column) const;
  // The raw text of a cell, trimmed ("" for a missing trailing cell).
  std::string text(std::size_t row, const std::string& column) const;

  // "FILE:LINE, column 'NAME' (N)" for error messages.
  std::string where(std::size_t row, const std::string& column) const;

 private:
  void add_line(std::string_view line, int line_no);
  std::string header_text() const;  // the header row, shortened for messages

  std::string path_;
  std::vector<std::string> header_;
  int header_line_ = 0;
  std::vector<std::vector<std::string>> cells_;
  std::vector<int> lines_;
};

}  // namespace terracal
