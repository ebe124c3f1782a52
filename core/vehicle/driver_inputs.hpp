#pragma once
// Driver inputs: what a driver (a file, or a built-in manoeuvre, core/vehicle/maneuver.hpp) gives a
// vehicle model at a time t: steering, throttle and braking.
//
// A driver file is a table of rows `time steering throttle braking`, the values separated by
// whitespace or commas (either, mixed), linear between rows -- the driver files of Project Chrono
// and of the LFDM vehicle models (uwsbel/low-fidelity-dynamic-models, data/input/*.txt) read as they
// are. Blank lines and lines whose first character (after spaces) is '#' are skipped. The file must
// be UTF-8 text (core/text_check.hpp). Every refusal is an InputError "PATH:LINE: column "NAME"
// value "TOKEN": expected ...":
//   - a token that is not a number, an infinite or NaN value, a number out of range for a double;
//   - a row with other than 4 values, an empty value between commas;
//   - a time that does not increase strictly (a repeated or decreasing time);
//   - steering outside [-1, 1], throttle or braking outside [0, 1];
//   - a file with no rows.
// The first time may be any finite number (negative too).
#include <string>
#include <vector>

#include "core/host_device.hpp"

namespace terracal {

struct DriverInput {
  double steering = 0;  // fraction of the maximum steering angle, -1..1; positive steers left (ISO 8855)
  double throttle = 0;  // 0..1
  double braking = 0;   // 0..1
};

// A view of a driver series that host and device code can read: plain pointers into arrays that the
// owner keeps alive (DriverSeries on the CPU; on a GPU, copies of its arrays in device memory).
struct DriverSeriesView {
  const double* time = nullptr;  // strictly increasing
  const double* steering = nullptr;
  const double* throttle = nullptr;
  const double* braking = nullptr;
  int n = 0;

  // Linear between rows; before the first row the first row's values, after the last row the last
  // row's values (a NaN time gives the first row's). Zero inputs for an empty view.
  TERRACAL_HD DriverInput at(double t) const {
    if (n <= 0) return DriverInput{};
    if (!(t > time[0])) return DriverInput{steering[0], throttle[0], braking[0]};
    if (t >= time[n - 1]) return DriverInput{steering[n - 1], throttle[n - 1], braking[n - 1]};
    return between(row_before(t, 0), t);
  }

  // The same value to the bit, for a run's times that increase from call to call: the search starts
  // at `cursor`, the row the previous call found, and walks forward, so a long series costs a step a
  // few reads instead of a bisection (on a GPU thread, a chain of dependent loads).
  TERRACAL_HD DriverInput at(double t, int& cursor) const {
    if (n <= 0 || !(t > time[0]) || t >= time[n - 1]) return at(t);
    int lo = cursor >= 0 && cursor < n - 1 && time[cursor] <= t ? cursor : row_before(t, 0);
    while (time[lo + 1] <= t) ++lo;
    cursor = lo;
    return between(lo, t);
  }

 private:
  // The last row at or before t (time[0] < t < time[n - 1]), by bisection from row lo.
  TERRACAL_HD int row_before(double t, int lo) const {
    int hi = n - 1;  // time[lo] < t < time[hi]
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      if (time[mid] <= t)
        lo = mid;
      else
        hi = mid;
    }
    return lo;
  }
  // Linear between row lo and the next.
  TERRACAL_HD DriverInput between(int lo, double t) const {
    const int hi = lo + 1;
    const double w = (t - time[lo]) / (time[hi] - time[lo]);
    return DriverInput{steering[lo] + w * (steering[hi] - steering[lo]),
                       throttle[lo] + w * (throttle[hi] - throttle[lo]), braking[lo] + w * (braking[hi] - braking[lo])};
  }
};

// A driver series on the CPU, read from a file or built from rows; never empty, times strictly
// increasing, every value in its range.
class DriverSeries {
 public:
  // Reads a driver file (the format above). Throws InputError "PATH:LINE: ..." for a bad file.
  static DriverSeries read(const std::string& path);
  // The same checks for rows built in code; messages name `source` and the row (1-based):
  // "SOURCE: row N: column "throttle" value 1.5: expected a number in [0, 1]". All four vectors must
  // have the same length.
  static DriverSeries from_rows(std::vector<double> time, std::vector<double> steering, std::vector<double> throttle,
                                std::vector<double> braking, const std::string& source = "driver rows");

  DriverInput at(double t) const { return view().at(t); }
  double start_time() const { return time_.front(); }
  double end_time() const { return time_.back(); }
  int size() const { return static_cast<int>(time_.size()); }
  // Valid while this series lives (and is not moved from).
  DriverSeriesView view() const {
    return DriverSeriesView{time_.data(), steering_.data(), throttle_.data(), braking_.data(), size()};
  }

  const std::vector<double>& times() const { return time_; }
  const std::vector<double>& steering() const { return steering_; }
  const std::vector<double>& throttle() const { return throttle_; }
  const std::vector<double>& braking() const { return braking_; }
  // The file's path, or the source given to from_rows.
  const std::string& source() const { return source_; }

 private:
  DriverSeries() = default;
  std::string source_;
  std::vector<double> time_, steering_, throttle_, braking_;
};

}  // namespace terracal
