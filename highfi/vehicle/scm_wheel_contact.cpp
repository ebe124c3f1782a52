#include "highfi/vehicle/scm_wheel_contact.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace terracal::vehicle {
namespace {
std::vector<lowfi::ScmWheelShape> shapes(const lowfi::ScmWheelShape& wheel, std::size_t n) {
  std::vector<lowfi::ScmWheelShape> out(n, wheel);
  for (std::size_t k = 0; k < n; ++k) out[k].name = fmt::format("wheel {}", k);
  return out;
}
terracal::Vec3<double> to_core(const mb::Vec3& v) { return {v.x(), v.y(), v.z()}; }
mb::Vec3 to_eigen(const terracal::Vec3<double>& v) { return {v.x, v.y, v.z}; }
}  // namespace

ScmWheelContact::ScmWheelContact(const lowfi::ScmSoil& soil, const lowfi::ScmSettings& settings,
                                 const lowfi::ScmWheelShape& wheel, std::size_t wheels)
    : soil_(soil, settings, shapes(wheel, wheels)), radius_(wheel.radius) {}

void ScmWheelContact::step(double t, const std::vector<mb::RigidBody>& bodies, const std::vector<int>& spindles) {
  std::vector<BodyState> states;
  for (int s : spindles) {
    const mb::RigidBody& b = bodies[std::size_t(s)];
    BodyState st;
    st.position = to_core(b.position);
    st.orientation = {b.orientation.w(), b.orientation.x(), b.orientation.y(), b.orientation.z()};
    st.velocity = to_core(b.velocity);
    st.omega = to_core(b.rotation() * b.omega);  // the terrain takes it in the world frame
    states.push_back(st);
  }
  soil_.step(states);
  previous_ = latest_.empty() ? soil_.wrenches() : latest_;
  latest_ = soil_.wrenches();
  stepped_at_ = t;
}

void ScmWheelContact::apply(std::size_t k, double t, const mb::RigidBody& spindle, mb::Wrench& w) const {
  if (latest_.empty()) return;
  const double a = std::clamp((t - stepped_at_) / soil_.time_step(), 0.0, 1.0);
  const BodyWrench &from = previous_[k], &to = latest_[k];
  w.force += to_eigen(from.force) + a * (to_eigen(to.force) - to_eigen(from.force));
  w.torque +=
      spindle.rotation().transpose() * (to_eigen(from.torque) + a * (to_eigen(to.torque) - to_eigen(from.torque)));
}

TireContact ScmWheelContact::contact(std::size_t k, const mb::RigidBody& spindle) const {
  const mb::Mat3 r = spindle.rotation();
  const mb::Vec3 axis = r.col(1), up(0, 0, 1);
  // The wheel's heading on the ground: along the ground, perpendicular to the spin axis.
  mb::Vec3 heading = axis.cross(up);
  heading = heading.norm() > 1e-9 ? heading.normalized() : mb::Vec3(1, 0, 0);
  const mb::Vec3 left = up.cross(heading);
  const mb::Vec3 force = to_eigen(soil_.wrenches()[k].force);
  TireContact c;
  c.fx = force.dot(heading), c.fy = force.dot(left), c.fz = force.z();
  // The wheel's own sinkage: the lowest point of its centre plane below the undisturbed surface (a
  // cambered wheel's edge sinks deeper; soil_.sinkage(k), the deepest node, would count that too).
  const double lowest = spindle.position.z() - radius_ * std::sqrt(std::max(0.0, 1 - axis.z() * axis.z()));
  c.sinkage = std::max(0.0, soil_.terrain().settings().surface_height - lowest);
  c.touching = soil_.contact_area(k) > 0;
  c.point = spindle.position - radius_ * up;
  const double vx = spindle.velocity.dot(heading), vy = spindle.velocity.dot(left);
  const double roll = (r * spindle.omega).dot(axis) * radius_;  // w R, positive rolling forward
  const double scale = std::max(std::abs(roll), std::abs(vx));
  c.sx = scale > 1e-3 ? (roll - vx) / scale : 0.0;
  c.sy = std::abs(vx) > 1e-3 ? -vy / std::abs(vx) : 0.0;
  return c;
}

}  // namespace terracal::vehicle
