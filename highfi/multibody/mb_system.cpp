#include "highfi/multibody/mb_system.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::mb {

int MbSystem::add_body(RigidBody b) {
  bodies.push_back(std::move(b));
  index();
  return int(bodies.size()) - 1;
}

int MbSystem::add_joint(const std::string& name, JointType type, int i, int j, const Vec3& where, const Mat3& axes,
                        const Vec3& other) {
  joints.push_back(Joint::place(name, type, bodies, i, j, where, axes, other));
  return int(joints.size()) - 1;
}

void MbSystem::index() {
  moving_.clear();
  slot_.assign(bodies.size(), -1);
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (!bodies[b].fixed) {
      slot_[b] = int(moving_.size());
      moving_.push_back(int(b));
    }
}

int MbSystem::position_rows() const {
  int m = 0;
  for (const Joint& j : joints) m += joint_rows(j.type);
  return m;
}

void MbSystem::get_positions(double* q) const {
  for (int k = 0; k < moving(); ++k) {
    const RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    double* p = q + 7 * k;
    p[0] = b.position.x(), p[1] = b.position.y(), p[2] = b.position.z();
    p[3] = b.orientation.w(), p[4] = b.orientation.x(), p[5] = b.orientation.y(), p[6] = b.orientation.z();
  }
  for (std::size_t k = 0; k < shafts.size(); ++k) q[7 * moving() + int(k)] = shafts[k].angle;
}

void MbSystem::set_positions(const double* q) {
  for (int k = 0; k < moving(); ++k) {
    RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    const double* p = q + 7 * k;
    b.position = Vec3(p[0], p[1], p[2]);
    // The integrator keeps |q| = 1 as a constraint; the rotation matrix is taken from the unit quaternion.
    b.orientation = Quat(p[3], p[4], p[5], p[6]).normalized();
  }
  for (std::size_t k = 0; k < shafts.size(); ++k) shafts[k].angle = q[7 * moving() + int(k)];
}

void MbSystem::get_velocities(double* u) const {
  for (int k = 0; k < moving(); ++k) {
    const RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    for (int c = 0; c < 3; ++c) u[6 * k + c] = b.velocity[c], u[6 * k + 3 + c] = b.omega[c];
  }
  for (std::size_t k = 0; k < shafts.size(); ++k) u[6 * moving() + int(k)] = shafts[k].speed;
}

void MbSystem::set_velocities(const double* u) {
  for (int k = 0; k < moving(); ++k) {
    RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    b.velocity = Vec3(u[6 * k], u[6 * k + 1], u[6 * k + 2]);
    b.omega = Vec3(u[6 * k + 3], u[6 * k + 4], u[6 * k + 5]);
  }
  for (std::size_t k = 0; k < shafts.size(); ++k) shafts[k].speed = u[6 * moving() + int(k)];
}

void MbSystem::coordinate_rates(const double* q, const double* u, double* qdot) const {
  for (int k = 0; k < moving(); ++k) {
    const double* p = q + 7 * k;
    const double* v = u + 6 * k;
    double* d = qdot + 7 * k;
    d[0] = v[0], d[1] = v[1], d[2] = v[2];
    const double w = p[3], x = p[4], y = p[5], z = p[6], a = v[3], b = v[4], c = v[5];
    // q (x) (0, w_body) / 2
    d[3] = 0.5 * (-x * a - y * b - z * c);
    d[4] = 0.5 * (w * a + y * c - z * b);
    d[5] = 0.5 * (w * b + z * a - x * c);
    d[6] = 0.5 * (w * c + x * b - y * a);
  }
  for (std::size_t k = 0; k < shafts.size(); ++k) qdot[7 * moving() + int(k)] = u[6 * moving() + int(k)];
}

void MbSystem::constraints(Eigen::VectorXd& phi, Eigen::MatrixXd& jac) const {
  std::vector<ConstraintRow> rows;
  rows.reserve(std::size_t(constraint_rows()));
  for (const Joint& j : joints) j.rows(bodies, rows);
  const Eigen::Index held = Eigen::Index(rows.size()), shaft0 = 6 * moving();
  std::vector<Row6> shaft_parts(shaft_bodies.size());
  for (std::size_t k = 0; k < shaft_bodies.size(); ++k) rows.push_back(shaft_bodies[k].row(bodies, shaft_parts[k]));
  phi.resize(held);
  jac.setZero(Eigen::Index(rows.size() + linkages.size()), velocities());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (Eigen::Index(r) < held) phi[Eigen::Index(r)] = rows[r].value;
    const int si = slot_[std::size_t(rows[r].i)], sj = slot_[std::size_t(rows[r].j)];
    if (si >= 0) jac.block<1, 6>(Eigen::Index(r), 6 * si) += rows[r].ji;
    if (sj >= 0) jac.block<1, 6>(Eigen::Index(r), 6 * sj) += rows[r].jj;
  }
  for (std::size_t k = 0; k < shaft_bodies.size(); ++k)
    jac(held + Eigen::Index(k), shaft0 + shaft_bodies[k].shaft) = shaft_parts[k][0];
  for (std::size_t k = 0; k < linkages.size(); ++k)
    for (std::size_t c = 0; c < linkages[k].shafts.size(); ++c)
      jac(Eigen::Index(rows.size() + k), shaft0 + linkages[k].shafts[c]) += linkages[k].coefficients[c];
}

Eigen::VectorXd MbSystem::applied(double t) const {
  std::vector<Wrench> w(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) w[b].force = bodies[b].mass * gravity;
  for (const auto& e : springs) e.apply(bodies, w);
  for (const auto& e : rotational_springs) e.apply(bodies, w);
  for (const auto& e : bushings) e.apply(bodies, w);
  for (const auto& f : external) f.apply(t, bodies, w);
  Eigen::VectorXd f(velocities());
  for (int k = 0; k < moving(); ++k) {
    const RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    f.segment<3>(6 * k) = w[std::size_t(moving_[std::size_t(k)])].force;
    f.segment<3>(6 * k + 3) = w[std::size_t(moving_[std::size_t(k)])].torque - b.omega.cross(b.inertia * b.omega);
  }
  const Eigen::Index shaft0 = 6 * moving();
  for (std::size_t k = 0; k < shafts.size(); ++k) f[shaft0 + Eigen::Index(k)] = 0;
  for (const ShaftTorque& st : shaft_torques) {
    const Shaft& sh = shafts[std::size_t(st.shaft)];
    f[shaft0 + st.shaft] += st.torque(t, sh.angle, sh.speed);
  }
  for (const ShaftPairTorque& e : shaft_pair_torques) {
    const auto [ta, tb] = e.torques(t, shafts[std::size_t(e.a)].speed, shafts[std::size_t(e.b)].speed);
    f[shaft0 + e.a] += ta;
    f[shaft0 + e.b] += tb;
  }
  for (const Clutch& c : clutches) {
    const double tq = c.torque(shafts[std::size_t(c.a)].speed, shafts[std::size_t(c.b)].speed);
    f[shaft0 + c.b] += tq;
    f[shaft0 + c.a] -= tq;
  }
  return f;
}

Eigen::MatrixXd MbSystem::mass_matrix() const {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(velocities(), velocities());
  for (int k = 0; k < moving(); ++k) {
    const RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
    m.block<3, 3>(6 * k, 6 * k) = b.mass * Mat3::Identity();
    m.block<3, 3>(6 * k + 3, 6 * k + 3) = b.inertia;
  }
  for (std::size_t k = 0; k < shafts.size(); ++k)
    m(6 * moving() + Eigen::Index(k), 6 * moving() + Eigen::Index(k)) = shafts[k].inertia;
  return m;
}

double MbSystem::mechanical_energy() const {
  double e = 0;
  for (const RigidBody& b : bodies) {
    if (b.fixed) continue;
    e += 0.5 * b.mass * b.velocity.squaredNorm() + 0.5 * b.omega.dot(b.inertia * b.omega);
    e -= b.mass * gravity.dot(b.position);
  }
  for (const Shaft& sh : shafts) e += 0.5 * sh.inertia * sh.speed * sh.speed;
  return e;
}

void MbSystem::assemble(double tolerance, int max_iterations) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd jac;
  constraints(phi, jac);
  if (jac.rows() == 0) return;
  const Eigen::FullPivLU<Eigen::MatrixXd> rank(jac);
  if (rank.rank() < jac.rows())
    throw InputError(
        fmt::format("multibody: {} constraint rows but only {} independent ones: the joints constrain "
                    "some motions twice (replace a revolute in a closed loop by a spherical or a "
                    "universal joint)",
                    jac.rows(), rank.rank()));
  for (int it = 0;; ++it) {
    if (phi.size() == 0 || phi.lpNorm<Eigen::Infinity>() <= tolerance) break;
    if (it == max_iterations)
      throw InputError(
          fmt::format("multibody: the joints cannot be assembled: constraint error {:.3g} after {} "
                      "iterations (are the hardpoints consistent?)",
                      phi.lpNorm<Eigen::Infinity>(), max_iterations));
    const Eigen::VectorXd step = jac.topRows(phi.size()).completeOrthogonalDecomposition().solve(-phi);  // least norm
    for (int k = 0; k < moving(); ++k) {
      RigidBody& b = bodies[std::size_t(moving_[std::size_t(k)])];
      b.position += step.segment<3>(6 * k);
      const Vec3 rot = step.segment<3>(6 * k + 3);
      if (rot.norm() > 0)
        b.orientation = (b.orientation * Quat(Eigen::AngleAxisd(rot.norm(), rot.normalized()))).normalized();
    }
    constraints(phi, jac);
  }
  // Velocities: the nearest (in kinetic energy) that meets Phi_v u = 0.
  Eigen::VectorXd u(velocities());
  get_velocities(u.data());
  const Eigen::MatrixXd minv = mass_matrix().inverse();
  const Eigen::MatrixXd s = jac * minv * jac.transpose();
  u -= minv * jac.transpose() * s.ldlt().solve(jac * u);
  set_velocities(u.data());
}

}  // namespace terracal::mb
