#include "highfi/multibody/force_elements.hpp"

#include <cmath>

namespace terracal::mb {
namespace {
// Piecewise linear through (x, y), extended linearly with the end segments' slopes.
double piecewise_linear(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.size() < 2) return y.empty() ? 0.0 : y[0];
  std::size_t k = 1;
  while (k + 1 < x.size() && x[k] < at) ++k;
  const double t = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + t * (y[k] - y[k - 1]);
}
}  // namespace

ForceLaw linear_law(double stiffness, double damping, double at_zero) {
  return [=](double x, double v) { return at_zero + stiffness * x + damping * v; };
}

ForceLaw table_law(std::vector<double> defl, std::vector<double> force, std::vector<double> rate,
                   std::vector<double> damper_force) {
  return [=](double x, double v) { return piecewise_linear(defl, force, x) + piecewise_linear(rate, damper_force, v); };
}

void add_force_at(const RigidBody& body, const Vec3& local, const Vec3& force, Wrench& w) {
  w.force += force;
  w.torque += local.cross(body.rotation().transpose() * force);
}

double SpringDamper::length(const std::vector<RigidBody>& b) const {
  return (b[std::size_t(j)].point(sj) - b[std::size_t(i)].point(si)).norm();
}

void SpringDamper::apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const {
  const RigidBody &bi = b[std::size_t(i)], &bj = b[std::size_t(j)];
  const Vec3 d = bj.point(sj) - bi.point(si);
  const double l = d.norm();
  if (l <= 0) return;  // coincident points: no direction to push along
  const Vec3 e = d / l;
  const double rate = e.dot(bj.point_velocity(sj) - bi.point_velocity(si));
  const double f = -law(l - rest_length, rate);  // pushes apart
  add_force_at(bj, sj, f * e, w[std::size_t(j)]);
  add_force_at(bi, si, -f * e, w[std::size_t(i)]);
}

double RotationalSpringDamper::angle(const std::vector<RigidBody>& b) const {
  const Mat3 Ai = b[std::size_t(i)].rotation(), Aj = b[std::size_t(j)].rotation();
  const Vec3 xi = Ai * frame_i.col(0), yi = Ai * frame_i.col(1), xj = Aj * frame_j.col(0);
  return std::atan2(xj.dot(yi), xj.dot(xi));
}

void RotationalSpringDamper::apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const {
  const RigidBody &bi = b[std::size_t(i)], &bj = b[std::size_t(j)];
  const Vec3 z = bi.rotation() * frame_i.col(2);
  const double rate = z.dot(bj.rotation() * bj.omega - bi.rotation() * bi.omega);
  const Vec3 torque = -law(angle(b), rate) * z;  // on j, world
  w[std::size_t(j)].torque += bj.rotation().transpose() * torque;
  w[std::size_t(i)].torque -= bi.rotation().transpose() * torque;
}

void Bushing::apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const {
  const RigidBody &bi = b[std::size_t(i)], &bj = b[std::size_t(j)];
  const Mat3 Fi = bi.rotation() * frame_i;  // frame i in the world
  const Vec3 dx = Fi.transpose() * (bj.point(sj) - bi.point(si));
  const Vec3 dv = Fi.transpose() * (bj.point_velocity(sj) - bi.point_velocity(si));
  // The relative rotation as a rotation vector, and the relative angular velocity, in frame i.
  const Eigen::AngleAxisd rel(Fi.transpose() * bj.rotation() * frame_j);
  const Vec3 dr = rel.angle() * rel.axis();
  const Vec3 dw = Fi.transpose() * (bj.rotation() * bj.omega - bi.rotation() * bi.omega);
  const Vec3 f = Fi * (-(k_lin.cwiseProduct(dx) + c_lin.cwiseProduct(dv)));
  const Vec3 t = Fi * (-(k_rot.cwiseProduct(dr) + c_rot.cwiseProduct(dw)));
  add_force_at(bj, sj, f, w[std::size_t(j)]);
  add_force_at(bi, si, -f, w[std::size_t(i)]);
  w[std::size_t(j)].torque += bj.rotation().transpose() * t;
  w[std::size_t(i)].torque -= bi.rotation().transpose() * t;
}

}  // namespace terracal::mb
