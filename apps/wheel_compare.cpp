#include "apps/wheel_compare.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace terracal::app {

std::map<std::string, std::vector<double>> read_csv_columns(const std::string& path) {
  std::map<std::string, std::vector<double>> out;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return out;
  std::vector<std::string> names;
  std::stringstream hs(line);
  for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::size_t c = 0;
    for (std::string v; std::getline(ls, v, ',') && c < names.size(); ++c) {
      try {
        out[names[c]].push_back(std::stod(v));  // "nan" and "inf" read as such
      } catch (const std::exception&) {
        out[names[c]].push_back(NAN);
      }
    }
  }
  return out;
}

double rmse_percent(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || b.empty()) return NAN;
  double s = 0, top = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    s += (a[i] - b[i]) * (a[i] - b[i]);
    top = std::max(top, std::fabs(b[i]));
  }
  return top > 0 ? 100.0 * std::sqrt(s / double(a.size())) / top : NAN;
}

std::string percent_text(double v) { return std::isfinite(v) ? fmt::format("{:.3g} %", v) : "–"; }

}  // namespace terracal::app
