#include "apps/wheel_band.hpp"

#include <exception>

#include <fmt/format.h>

#include "apps/soil_choice.hpp"
#include "bayes/diagnostics.hpp"
#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "lowfi/scm_steady_wheel.hpp"

namespace terracal::app {

namespace {
std::array<double, 3> steady(const lowfi::ScmSoil& set, const rigs::WheelSpec& wheel, double load, double slip,
                             bool slip_sinkage) {
  lowfi::ScmSteadyWheelOptions o;
  o.angular_velocity = wheel.angular_velocity;
  o.slip_sinkage = slip_sinkage;
  o.rel_tol = 1e-6;
  const auto r = lowfi::scm_steady_wheel(set, {wheel.radius, wheel.width}, load, slip, o);
  return {r.dbp, r.torque, r.sinkage};
}
}  // namespace

WheelBand scm_wheel_band(const std::vector<lowfi::ScmSoil>& sets, const rigs::WheelSpec& wheel, const Vec3<double>& gravity,
                         const std::vector<double>& slips, bool slip_sinkage, const TerrainOptions& scm_options,
                         const rigs::WheelRun& run, int checks) {
  WheelBand b;
  b.slips = slips;
  const double load = wheel.mass * norm(gravity);
  std::vector<std::array<std::vector<double>, 3>> per_slip(slips.size());
  for (const lowfi::ScmSoil& set : sets) {
    std::vector<std::array<double, 3>> row;
    try {
      for (double s : slips) row.push_back(steady(set, wheel, load, s, slip_sinkage));
    } catch (const std::exception&) {
      ++b.failed;  // no steady state for this set (e.g. no strength on the wheel's patch)
      continue;
    }
    ++b.sets;
    for (std::size_t i = 0; i < slips.size(); ++i)
      for (int c = 0; c < 3; ++c) per_slip[i][c].push_back(row[i][c]);
  }
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < slips.size() && b.sets > 0; ++i) {
      b.q05[c].push_back(bayes::quantile(per_slip[i][c], 0.05));
      b.q50[c].push_back(bayes::quantile(per_slip[i][c], 0.5));
      b.q95[c].push_back(bayes::quantile(per_slip[i][c], 0.95));
    }
  if (sets.empty() || slips.empty() || checks <= 0) return b;
  b.check_slip = slips[slips.size() / 2];
  SoilChoice scm;
  scm.solver = SoilModel::kScm;
  scm.gravity = gravity;
  for (int k = 0; k < checks; ++k) {
    const lowfi::ScmSoil& set = sets[(sets.size() - 1) * k / std::max(1, checks - 1)];
    try {
      const auto steady_value = steady(set, wheel, load, b.check_slip, slip_sinkage);
      scm.scm = set;
      const auto stepped = run_wheel_sweep(SoilModel::kScm, scm, scm_options, wheel, {b.check_slip}, run);
      b.check_steady.push_back(steady_value);
      b.check_stepped.push_back({stepped[0].dbp, stepped[0].torque, stepped[0].sinkage});
    } catch (const std::exception&) {
      // A set neither model can carry is counted among `failed` above; no check for it.
    }
  }
  return b;
}

void write_wheel_band_csv(const std::string& path, const WheelBand& b) {
  std::string s = "slip,dbp_q05_N,dbp_q50_N,dbp_q95_N,torque_q05_Nm,torque_q50_Nm,torque_q95_Nm,sinkage_q05_m,"
                  "sinkage_q50_m,sinkage_q95_m\n";
  for (std::size_t i = 0; i < b.q05[0].size(); ++i) {
    s += fmt::format("{:.6g}", b.slips[i]);
    for (int c = 0; c < 3; ++c) s += fmt::format(",{:.9g},{:.9g},{:.9g}", b.q05[c][i], b.q50[c][i], b.q95[c][i]);
    s += "\n";
  }
  write_text_atomically(path, s);
}

WheelBand read_wheel_band_csv(const std::string& path) {
  WheelBand b;
  const CsvTable t = CsvTable::read(path);
  const char* names[3][3] = {{"dbp_q05_N", "dbp_q50_N", "dbp_q95_N"},
                             {"torque_q05_Nm", "torque_q50_Nm", "torque_q95_Nm"},
                             {"sinkage_q05_m", "sinkage_q50_m", "sinkage_q95_m"}};
  for (std::size_t i = 0; i < t.rows(); ++i) {
    b.slips.push_back(t.number(i, "slip"));
    for (int c = 0; c < 3; ++c) {
      b.q05[c].push_back(t.number(i, names[c][0]));
      b.q50[c].push_back(t.number(i, names[c][1]));
      b.q95[c].push_back(t.number(i, names[c][2]));
    }
  }
  return b;
}

}  // namespace terracal::app
