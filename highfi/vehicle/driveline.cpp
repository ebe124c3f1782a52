#include "highfi/vehicle/driveline.hpp"

namespace terracal::vehicle {

namespace {
int add_shaft(mb::MbSystem& s, const std::string& name, double inertia) {
  s.shafts.push_back({name, inertia, 0.0, 0.0});
  return int(s.shafts.size()) - 1;
}
}  // namespace

Driveline build_driveline(mb::MbSystem& s, const PowertrainParams& p, const DrivelineSpec& spec,
                          const std::vector<WishboneSide>& corners, const std::vector<double>& axle_inertias,
                          const DriverFunction* driver) {
  Driveline d;
  const std::size_t axles = corners.size() / 2;
  d.crank = add_shaft(s, "crank", p.crank_inertia);
  d.turbine = add_shaft(s, "gearbox input", spec.turbine_inertia);
  d.driveshaft = add_shaft(s, "driveshaft", spec.driveshaft_inertia);
  d.gearbox = int(s.linkages.size());
  s.linkages.push_back(mb::gear("gearbox", d.turbine, d.driveshaft, p.gear_ratio[0]));
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const int shaft = add_shaft(s, "axle shaft", axle_inertias[k / 2]);
    d.axle_shafts.push_back(shaft);
    s.shaft_bodies.push_back({"wheel spin", shaft, corners[k].upright, corners[k].spindle, Vec3::UnitY()});
  }
  // Which axles are driven: the first is the front, the last the rear.
  std::vector<int> driven;
  for (std::size_t a = 0; a < axles; ++a) {
    const bool front = a == 0;
    if (is_driven(p.drive, front) && (front || a + 1 == axles)) driven.push_back(int(a));
  }
  d.axle_driveshafts.assign(axles, -1);
  if (driven.size() == 1) {
    d.axle_driveshafts[std::size_t(driven[0])] = d.driveshaft;
  } else {
    for (int a : driven)
      d.axle_driveshafts[std::size_t(a)] = add_shaft(s, "axle driveshaft", spec.axle_driveshaft_inertia);
    s.linkages.push_back(mb::differential("central differential", d.driveshaft,
                                          d.axle_driveshafts[std::size_t(driven[0])],
                                          d.axle_driveshafts[std::size_t(driven[1])]));
  }
  for (int a : driven)
    s.linkages.push_back(mb::differential("axle differential", d.axle_driveshafts[std::size_t(a)],
                                          d.axle_shafts[std::size_t(2 * a)], d.axle_shafts[std::size_t(2 * a + 1)]));
  const PowertrainParams params = p;
  s.shaft_torques.push_back({"engine", d.crank, [params, driver](double t, double, double w) {
                               return engine_torque(params, w, (*driver)(t).throttle);
                             }});
  s.shaft_pair_torques.push_back({"torque converter", d.crank, d.turbine, [params](double, double wc, double wt) {
                                    const ConverterTorques c = torque_converter(params, wc, wt);
                                    return std::pair<double, double>(-c.pump, c.turbine);
                                  }});
  // Brakes: dry friction between each spindle and its upright about the spin axis.
  for (const WishboneSide& c : corners)
    s.external.push_back(
        {[params, driver, c](double t, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& w) {
           const double braking = (*driver)(t).braking;
           if (braking <= 0) return;
           const mb::RigidBody &sp = b[std::size_t(c.spindle)], &up = b[std::size_t(c.upright)];
           const Vec3 axis = up.rotation() * Vec3::UnitY();
           const double spin = axis.dot(sp.rotation() * sp.omega - up.rotation() * up.omega);
           const Vec3 torque = dry_friction_torque(braking * params.max_brake_torque, spin) * axis;
           w[std::size_t(c.spindle)].torque += sp.rotation().transpose() * torque;
           w[std::size_t(c.upright)].torque -= up.rotation().transpose() * torque;
         },
         {c.spindle, c.upright}});
  return d;
}

void set_gear(mb::MbSystem& s, const PowertrainParams& p, Driveline& d, int gear) {
  d.gear = gear;
  s.linkages[std::size_t(d.gearbox)] = mb::gear("gearbox", d.turbine, d.driveshaft, p.gear_ratio[gear]);
}

bool update_gear(mb::MbSystem& s, const PowertrainParams& p, Driveline& d) {
  const int gear = shift_gear(p, d.gear, s.shafts[std::size_t(d.turbine)].speed);
  if (gear == d.gear) return false;
  set_gear(s, p, d, gear);
  return true;
}

}  // namespace terracal::vehicle
