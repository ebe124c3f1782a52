#pragma once
// Comparing single-wheel sweeps read back from their wheel.csv files: what the campaign report and
// the studies measure one run against another with.
#include <map>
#include <string>
#include <vector>

namespace terracal::app {

// A CSV file's columns by header name (empty when the file is missing or has no header; a cell that
// is not a number is NaN).
std::map<std::string, std::vector<double>> read_csv_columns(const std::string& path);

// RMSE of a against b in percent of b's largest magnitude (not its range: SCM's sinkage hardly
// changes with slip, and a range near zero would blow small differences up); NaN when the lengths
// differ, b is empty or all zero.
double rmse_percent(const std::vector<double>& a, const std::vector<double>& b);

// "12.3 %", or "–" for NaN.
std::string percent_text(double v);

}  // namespace terracal::app
