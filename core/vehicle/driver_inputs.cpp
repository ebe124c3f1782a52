#include "core/vehicle/driver_inputs.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal {
namespace {

constexpr int kColumns = 4;
constexpr const char* kNames[kColumns] = {"time", "steering", "throttle", "braking"};
// Driver rows are a few dozen characters; a much longer line is not a driver row (as in core/csv.cpp).
constexpr std::size_t kMaxLineBytes = 64 * 1024;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// One value of a row: its text (for messages) and the number it reads as.
struct Cell {
  std::string_view token;
  double value = 0;
};

// The checks of one row that the file reader and from_rows share. `where` is "PATH:LINE" or
// "SOURCE: row N", `shown` the values as the input gave them, `previous` the row before (if any) and
// `previous_where` where it was ("line 7", "row 6").
void check_row(const double v[kColumns], const std::string shown[kColumns], const std::string& where,
               const double* previous_time, const std::string& previous_where) {
  for (int c = 0; c < kColumns; ++c)
    if (!std::isfinite(v[c]))
      throw InputError(
          fmt::format("{}: column \"{}\" value \"{}\": expected a finite number", where, kNames[c], shown[c]));
  if (previous_time && !(v[0] > *previous_time))
    throw InputError(fmt::format(
        "{}: column \"time\" value \"{}\": expected a time greater than {} (the time on {}); times must increase "
        "strictly",
        where, shown[0], *previous_time, previous_where));
  if (!(v[1] >= -1 && v[1] <= 1))
    throw InputError(fmt::format(
        "{}: column \"steering\" value \"{}\": expected a number in [-1, 1] (a fraction of the maximum steering angle)",
        where, shown[1]));
  for (int c = 2; c < kColumns; ++c)
    if (!(v[c] >= 0 && v[c] <= 1))
      throw InputError(
          fmt::format("{}: column \"{}\" value \"{}\": expected a number in [0, 1]", where, kNames[c], shown[c]));
}

// Splits a row at whitespace and commas: "0 0.5,1 , 0" has the four values 0, 0.5, 1, 0. A comma
// must stand between two values ("1,,2" and a trailing comma are refused).
std::vector<std::string_view> split_row(std::string_view line, const std::string& where) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  const auto skip_space = [&] {
    while (i < line.size() && is_space(line[i])) ++i;
  };
  skip_space();
  while (i < line.size()) {
    const std::size_t b = i;
    while (i < line.size() && !is_space(line[i]) && line[i] != ',') ++i;
    if (i == b)
      throw InputError(
          fmt::format("{}: an empty value before a comma in {}; expected {} numbers such as 0.5 "
                      "separated by spaces or commas",
                      where, excerpt(line), kColumns));
    out.push_back(line.substr(b, i - b));
    skip_space();
    if (i < line.size() && line[i] == ',') {
      ++i;
      skip_space();
      if (i == line.size())
        throw InputError(
            fmt::format("{}: the row {} ends with a comma; expected {} numbers such as 0.5 "
                        "separated by spaces or commas",
                        where, excerpt(line), kColumns));
    }
  }
  return out;
}

// The number a token reads as. Throws InputError naming the column and the token for text, an
// overflowing number (1e309) or one that rounds to zero (1e-400). "inf" and "nan" read here and are
// refused by check_row.
double parse_number(std::string_view token, int column, const std::string& where, bool first_row) {
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);  // from_chars does not take '+'
  double v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ptr != digits.data() + digits.size() || ec == std::errc::invalid_argument) {
    // A header row is the likeliest reason for text in the first row.
    const char* hint = first_row ? " (a header row? driver files have none: make it a comment with '#')" : "";
    throw InputError(fmt::format("{}: column \"{}\" value \"{}\": expected a number such as 0.5 or 1e-3{}", where,
                                 kNames[column], shorten(token), hint));
  }
  if (ec == std::errc::result_out_of_range)
    throw InputError(fmt::format("{}: column \"{}\": {}", where, kNames[column], out_of_range_number(token)));
  return v;
}

}  // namespace

DriverSeries DriverSeries::read(const std::string& path) {
  const std::string bytes = read_input_bytes(path, "driver file");
  const std::string_view text = check_utf8_text(path, bytes);
  DriverSeries s;
  s.source_ = path;
  int line_no = 0, previous_line = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_no;
    const std::string where = fmt::format("{}:{}", path, line_no);
    if (line.size() > kMaxLineBytes)
      throw InputError(fmt::format("{}: the line is longer than {} bytes: found {}; expected a row of {} numbers",
                                   where, kMaxLineBytes, excerpt(line), kColumns));
    const std::size_t first = line.find_first_not_of(" \t\r\v\f");
    if (first == std::string_view::npos || line[first] == '#') continue;
    const std::vector<std::string_view> tokens = split_row(line, where);
    if (tokens.size() != kColumns)
      throw InputError(fmt::format("{}: found {} values in {}; expected {}: time steering throttle braking", where,
                                   tokens.size(), excerpt(line), kColumns));
    double v[kColumns];
    std::string shown[kColumns];
    for (int c = 0; c < kColumns; ++c) {
      v[c] = parse_number(tokens[c], c, where, s.time_.empty());
      shown[c] = shorten(tokens[c]);
    }
    check_row(v, shown, where, s.time_.empty() ? nullptr : &s.time_.back(), fmt::format("line {}", previous_line));
    s.time_.push_back(v[0]);
    s.steering_.push_back(v[1]);
    s.throttle_.push_back(v[2]);
    s.braking_.push_back(v[3]);
    previous_line = line_no;
  }
  if (s.time_.empty())
    throw InputError(
        fmt::format("{}: the driver file has no rows; expected rows of {} numbers: time steering "
                    "throttle braking",
                    path, kColumns));
  return s;
}

DriverSeries DriverSeries::from_rows(std::vector<double> time, std::vector<double> steering,
                                     std::vector<double> throttle, std::vector<double> braking,
                                     const std::string& source) {
  if (time.size() != steering.size() || time.size() != throttle.size() || time.size() != braking.size())
    throw InputError(
        fmt::format("{}: the columns have different lengths (time {}, steering {}, throttle {}, "
                    "braking {}); expected one value of each per row",
                    source, time.size(), steering.size(), throttle.size(), braking.size()));
  if (time.empty())
    throw InputError(fmt::format("{}: no rows; expected at least one row of time steering throttle braking", source));
  for (std::size_t r = 0; r < time.size(); ++r) {
    const double v[kColumns] = {time[r], steering[r], throttle[r], braking[r]};
    std::string shown[kColumns];
    for (int c = 0; c < kColumns; ++c) shown[c] = fmt::format("{}", v[c]);
    check_row(v, shown, fmt::format("{}: row {}", source, r + 1), r ? &time[r - 1] : nullptr, fmt::format("row {}", r));
  }
  DriverSeries s;
  s.source_ = source;
  s.time_ = std::move(time);
  s.steering_ = std::move(steering);
  s.throttle_ = std::move(throttle);
  s.braking_ = std::move(braking);
  return s;
}

}  // namespace terracal
