// What separates the SCM wheel from Wong-Reece, one assumption at a time. The
// ladder starts at the SCM wheel of the comparison (run.sh: damping on, the set's elastic stiffness)
// and ends at Wong-Reece, changing one thing per row:
//   1 SCM as compared            damping pressure R v_n, rear elastic rebound (Ke of the set)
//   2 SCM, no damping            rear rebound only
//   3 SCM, stiff soil            Ke = 2e9 Pa/m: the rear carries nothing (rebound ~ 15 um)
//   4 integral, SCM's wheel      quadrature: peak stress at the bottom (c1 = c2 = 0), shear per ground point
//   5 integral, rim shear        the same with Wong-Reece's shear displacement along the rim
//   6 Wong-Reece                 peak at theta_m = (0.43 + 0.32 s) theta1, mirrored onto the rear
// Rows 3 and 4 are the same wheel computed two ways (the test "SCM wheel matches the rigid-wheel
// integrals under SCM's own assumptions" bounds their difference).
// Usage: scm_wr_decomposition SCM.json [OUT.md]   (the default wheel: r 0.47 m, b 0.25 m, 108 kg, 1 rad/s;
// SCM at 0.01 m and 1e-3 s, 4 s per slip, means over the second half, as run.sh)
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"
#include "lowfi/wong_reece.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

using namespace terracal;

namespace {

struct Row {
  std::string name, what;
  std::vector<rigs::WheelResult> at;  // one per slip
};

const std::vector<double> kSlips{0.1, 0.3, 0.5};

Row scm_row(const std::string& name, const std::string& what, const lowfi::ScmSoil& soil, bool damping) {
  lowfi::ScmSettings s;
  s.grid = 0.01;
  s.time_step = 1e-3;
  if (damping) s.effects.enable<lowfi::ScmDamping>();
  const lowfi::ScmSite site(soil, s);
  rigs::WheelRun run;
  run.duration = 4.0;
  run.average_from = 0.5;
  Row row{name, what, {}};
  for (double slip : kSlips) row.at.push_back(rigs::run_wheel(site, rigs::WheelSpec{}, slip, run));
  return row;
}

Row integral_row(const std::string& name, const std::string& what, const lowfi::ScmSoil& soil, double load,
                 const lowfi::WongReeceOptions& o) {
  const rigs::WheelSpec w;
  Row row{name, what, {}};
  for (double slip : kSlips) {
    const auto r = lowfi::wong_reece(soil, {w.radius, w.width}, load, slip, o);
    rigs::WheelResult out;
    out.slip = slip;
    out.load = load;
    out.dbp = r.dbp;
    out.torque = r.torque;
    out.sinkage = r.sinkage;
    row.at.push_back(out);
  }
  return row;
}

std::string table(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| row | model | what changes from the row above |";
  for (double s : kSlips) md << fmt::format(" s = {}: DBP / torque / sinkage |", s);
  md << "\n|---|---|---|";
  for (std::size_t i = 0; i < kSlips.size(); ++i) md << "---|";
  md << "\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    md << fmt::format("| {} | {} | {} |", k + 1, rows[k].name, rows[k].what);
    for (const auto& r : rows[k].at)
      md << fmt::format(" {:.0f} N / {:.0f} N m / {:.4f} m |", r.dbp, r.torque, r.sinkage);
    md << "\n";
  }
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s SCM.json [OUT.md]\n", argv[0]);
    return 2;
  }
  try {
    const lowfi::ScmSoil soil = lowfi::read_scm_json(argv[1]);
    lowfi::ScmSoil stiff = soil;
    stiff.elastic_stiffness = 2e9;
    std::vector<Row> rows;
    rows.push_back(scm_row("SCM as compared", "(damping pressure, rear rebound)", soil, true));
    rows.push_back(scm_row("SCM", "no damping pressure", soil, false));
    rows.push_back(scm_row("SCM", "Ke 2e9 Pa/m: no rear rebound", stiff, false));
    const double load = rows.front().at.front().load;
    lowfi::WongReeceOptions scm_like;
    scm_like.c1 = scm_like.c2 = 0;
    scm_like.shear_displacement = lowfi::ShearDisplacement::ground;
    rows.push_back(integral_row("integral", "quadrature instead of nodes (peak at the bottom, shear per ground point)",
                                stiff, load, scm_like));
    lowfi::WongReeceOptions rim = scm_like;
    rim.shear_displacement = lowfi::ShearDisplacement::rim;
    rows.push_back(integral_row("integral", "shear displacement along the rim", stiff, load, rim));
    rows.push_back(
        integral_row("Wong-Reece", "peak stress at (0.43 + 0.32 s) theta1, mirrored to the rear", soil, load, {}));
    const std::string md = table(rows);
    std::cout << md;
    if (argc == 3) write_text_atomically(argv[2], md);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scm_wr_decomposition: %s\n", e.what());
    return 1;
  }
  return 0;
}
