#include "highfi/multibody/ggl_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace terracal::mb {
namespace {

// d/dq of q (x) (0, w) / 2 for body angular velocity w = (a, b, c): the 4 x 4 matrix.
Eigen::Matrix4d rate_of_quaternion_rates(const Vec3& w) {
  const double a = w.x(), b = w.y(), c = w.z();
  Eigen::Matrix4d m;
  m << 0, -a, -b, -c, a, 0, c, -b, b, -c, 0, a, c, b, -a, 0;
  return 0.5 * m;
}

// d/dw of q (x) (0, w) / 2: the 4 x 3 matrix G(q).
Eigen::Matrix<double, 4, 3> quaternion_rate_map(const Eigen::Vector4d& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Eigen::Matrix<double, 4, 3> g;
  g << -x, -y, -z, w, -z, y, z, w, -x, -y, x, w;
  return 0.5 * g;
}

// The body-frame rotation angle that a change dq of the raw (not unit) quaternion q causes once
// normalised: 2 vec(n* (x) dq) / |q| with n = q / |q| (3 x 4).
Eigen::Matrix<double, 3, 4> rotation_of_quaternion(const Eigen::Vector4d& q) {
  const double norm = q.norm();
  const Eigen::Vector4d n = q / norm;
  const Vec3 v = n.tail<3>();
  Eigen::Matrix<double, 3, 4> e;
  e.col(0) = -v;
  e.rightCols<3>() = n[0] * Mat3::Identity() - skew(v);
  return 2 * e / norm;
}

double difference_step(double value) { return 1.5e-8 * std::max(1.0, std::abs(value)); }

}  // namespace

GglJacobian::GglJacobian(MbSystem& system) : s_(system) {
  s_.index();
  nb_ = s_.moving();
  ns_ = int(s_.shafts.size());
  nq_ = s_.coordinates();
  nu_ = s_.velocities();
  m_ = s_.constraint_rows();
  mh_ = s_.position_rows();
  size_ = nq_ + nu_ + m_ + mh_ + nb_;
  build_blocks();
  build_coloring();
}

void GglJacobian::build_blocks() {
  blocks_.clear();
  int row = 0;
  const auto moving_slots = [&](std::initializer_list<int> bodies) {
    std::vector<int> out;
    for (int b : bodies)
      if (s_.slot(b) >= 0 && std::find(out.begin(), out.end(), s_.slot(b)) == out.end()) out.push_back(s_.slot(b));
    return out;
  };
  for (std::size_t k = 0; k < s_.joints.size(); ++k) {
    const Joint& j = s_.joints[k];
    blocks_.push_back({row, joint_rows(j.type), int(k), -1, moving_slots({j.i, j.j})});
    row += joint_rows(j.type);
  }
  for (std::size_t k = 0; k < s_.shaft_bodies.size(); ++k) {
    const ShaftToBody& sb = s_.shaft_bodies[k];
    blocks_.push_back({row, 1, -1, int(k), moving_slots({sb.i, sb.j})});
    ++row;
  }
}

// Nodes are the moving bodies (by slot) and then the shafts. Two nodes are neighbours when a force
// element (or external force, or shaft torque) reads one and writes the other; two nodes whose
// neighbourhoods overlap never share a colour, so that one evaluation of the forces per colour and
// coordinate separates every node's columns.
void GglJacobian::build_coloring() {
  const int nodes = nb_ + ns_;
  std::vector<std::set<int>> near(static_cast<std::size_t>(nodes));
  for (int n = 0; n < nodes; ++n) near[std::size_t(n)].insert(n);
  const auto couple = [&](const std::vector<int>& group) {
    for (int a : group)
      for (int b : group) near[std::size_t(a)].insert(b);
  };
  const auto bodies = [&](std::initializer_list<int> list) {
    std::vector<int> out;
    for (int b : list)
      if (s_.slot(b) >= 0) out.push_back(s_.slot(b));
    return out;
  };
  for (const auto& e : s_.springs) couple(bodies({e.i, e.j}));
  for (const auto& e : s_.rotational_springs) couple(bodies({e.i, e.j}));
  for (const auto& e : s_.bushings) couple(bodies({e.i, e.j}));
  for (const auto& e : s_.external) {
    std::vector<int> group;
    if (e.bodies.empty())
      for (int k = 0; k < nb_; ++k) group.push_back(k);
    else
      for (int b : e.bodies)
        if (s_.slot(b) >= 0) group.push_back(s_.slot(b));
    couple(group);
  }
  for (const auto& e : s_.shaft_pair_torques) couple({nb_ + e.a, nb_ + e.b});
  for (const auto& e : s_.clutches) couple({nb_ + e.a, nb_ + e.b});
  neighbours_.assign(std::size_t(nodes), {});
  for (int n = 0; n < nodes; ++n)
    neighbours_[std::size_t(n)].assign(near[std::size_t(n)].begin(), near[std::size_t(n)].end());
  // Greedy distance-2 colouring.
  std::vector<int> color(std::size_t(nodes), -1);
  color_nodes_.clear();
  for (int n = 0; n < nodes; ++n) {
    std::set<int> taken;
    for (int a : neighbours_[std::size_t(n)])
      for (int b : neighbours_[std::size_t(a)])
        if (color[std::size_t(b)] >= 0) taken.insert(color[std::size_t(b)]);
    int c = 0;
    while (taken.count(c)) ++c;
    color[std::size_t(n)] = c;
    if (c == int(color_nodes_.size())) color_nodes_.emplace_back();
    color_nodes_[std::size_t(c)].push_back(n);
  }
}

const Eigen::SparseMatrix<double>& GglJacobian::evaluate(double t, const double* y, double cj) {
  const Eigen::Map<const Eigen::VectorXd> u(y + nq_, nu_), mu(y + nq_ + nu_ + m_, mh_);
  s_.set_positions(y);
  s_.set_velocities(y + nq_);
  s_.constraints(phi_, jac_);
  f0_ = s_.applied(t);
  triplets_.clear();
  const Eigen::VectorXd corrected = u + jac_.topRows(mh_).transpose() * mu;
  kinematic_rows(y, corrected, cj);
  for (int k = 0; k < nb_; ++k)  // the kinematic rows' mu_n columns
    for (int c = 0; c < 4; ++c) {
      add(7 * k + 3 + c, 7 * k + 3 + c, -y[nq_ + nu_ + m_ + mh_ + k]);
      add(7 * k + 3 + c, nq_ + nu_ + m_ + mh_ + k, -y[7 * k + 3 + c]);
    }
  mass_and_multiplier_columns(cj);
  constraint_rows(y);
  applied_force_columns(t, y);
  joint_second_derivatives(y);
  s_.set_positions(y);
  s_.set_velocities(y + nq_);
  matrix_.resize(size_, size_);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  return matrix_;
}

// Rows q' - H(q) (u + Phi_v^T mu): cj I, -H against u and mu, and the quaternion rates' own q-derivative.
void GglJacobian::kinematic_rows(const double* y, const Eigen::VectorXd& corrected, double cj) {
  const Eigen::Map<const Eigen::VectorXd> q(y, nq_);
  for (int r = 0; r < nq_; ++r) add(r, r, cj);
  for (int k = 0; k < nb_; ++k) {
    for (int c = 0; c < 3; ++c) add(7 * k + c, nq_ + 6 * k + c, -1);
    const Eigen::Matrix<double, 4, 3> g = quaternion_rate_map(q.segment<4>(7 * k + 3));
    const Eigen::Matrix4d dq = rate_of_quaternion_rates(corrected.segment<3>(6 * k + 3));
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 3; ++c) add(7 * k + 3 + r, nq_ + 6 * k + 3 + c, -g(r, c));
      for (int c = 0; c < 4; ++c) add(7 * k + 3 + r, 7 * k + 3 + c, -dq(r, c));
    }
  }
  for (int sh = 0; sh < ns_; ++sh) add(7 * nb_ + sh, nq_ + 6 * nb_ + sh, -1);
  // -H Phi_v^T against mu, row by row of the position constraints.
  const int mu0 = nq_ + nu_ + m_;
  for (const Block& b : blocks_) {
    if (b.joint < 0) continue;
    for (int r = b.row0; r < b.row0 + b.rows; ++r)
      for (int k : b.slots) {
        const Eigen::Matrix<double, 4, 3> g = quaternion_rate_map(q.segment<4>(7 * k + 3));
        const Vec3 lin = jac_.block<1, 3>(r, 6 * k).transpose(), ang = jac_.block<1, 3>(r, 6 * k + 3).transpose();
        for (int c = 0; c < 3; ++c) add(7 * k + c, mu0 + r, -lin[c]);
        const Eigen::Vector4d qa = g * ang;
        for (int c = 0; c < 4; ++c) add(7 * k + 3 + c, mu0 + r, -qa[c]);
      }
  }
}

// Rows M u' - f + Phi_v^T lambda against u' (cj M) and lambda; rows Phi_v u against u.
void GglJacobian::mass_and_multiplier_columns(double cj) {
  for (int k = 0; k < nb_; ++k) {
    const RigidBody& body = s_.bodies[std::size_t(s_.body_in_slot(k))];
    for (int c = 0; c < 3; ++c) add(nq_ + 6 * k + c, nq_ + 6 * k + c, cj * body.mass);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) add(nq_ + 6 * k + 3 + r, nq_ + 6 * k + 3 + c, cj * body.inertia(r, c));
  }
  for (int sh = 0; sh < ns_; ++sh) add(nq_ + 6 * nb_ + sh, nq_ + 6 * nb_ + sh, cj * s_.shafts[std::size_t(sh)].inertia);
  const int lambda0 = nq_ + nu_, vel0 = nq_ + nu_ + mh_ + nb_;
  const auto both = [&](int r, int col) {
    add(nq_ + col, lambda0 + r, jac_(r, col));
    add(vel0 + r, nq_ + col, jac_(r, col));
  };
  for (const Block& b : blocks_)
    for (int r = b.row0; r < b.row0 + b.rows; ++r) {
      for (int k : b.slots)
        for (int c = 0; c < 6; ++c) both(r, 6 * k + c);
      if (b.shaft_body >= 0) both(r, 6 * nb_ + s_.shaft_bodies[std::size_t(b.shaft_body)].shaft);
    }
  const int linkage0 = blocks_.empty() ? 0 : blocks_.back().row0 + blocks_.back().rows;
  for (std::size_t k = 0; k < s_.linkages.size(); ++k)
    for (int sh : s_.linkages[k].shafts) both(linkage0 + int(k), 6 * nb_ + sh);
}

// Rows Phi (exact: Phi_v with the rotation that a quaternion change makes) and the quaternion norms.
void GglJacobian::constraint_rows(const double* y) {
  const int phi0 = nq_ + nu_;
  for (const Block& b : blocks_) {
    if (b.joint < 0) continue;
    for (int k : b.slots) {
      const Eigen::Matrix<double, 3, 4> e = rotation_of_quaternion(Eigen::Map<const Eigen::Vector4d>(y + 7 * k + 3));
      for (int r = b.row0; r < b.row0 + b.rows; ++r) {
        for (int c = 0; c < 3; ++c) add(phi0 + r, 7 * k + c, jac_(r, 6 * k + c));
        const Eigen::RowVector4d dq = jac_.block<1, 3>(r, 6 * k + 3) * e;
        for (int c = 0; c < 4; ++c) add(phi0 + r, 7 * k + 3 + c, dq[c]);
      }
    }
  }
  for (int k = 0; k < nb_; ++k)
    for (int c = 0; c < 4; ++c) add(phi0 + mh_ + k, 7 * k + 3 + c, y[7 * k + 3 + c]);
}

// -df/dq and -df/du by forward differences, one force evaluation per colour and coordinate.
void GglJacobian::applied_force_columns(double t, const double* y) {
  const auto qcol = [&](int n) { return n < nb_ ? 7 * n : 7 * nb_ + (n - nb_); };
  const auto ucol = [&](int n) { return n < nb_ ? 6 * n : 6 * nb_ + (n - nb_); };
  const auto udim = [&](int n) { return n < nb_ ? 6 : 1; };
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(y, nq_), u = Eigen::Map<const Eigen::VectorXd>(y + nq_, nu_);
  for (const std::vector<int>& group : color_nodes_)
    for (int part = 0; part < 2; ++part)  // coordinates, then velocities
      for (int d = 0; d < (part == 0 ? 7 : 6); ++d) {
        Eigen::VectorXd& x = part == 0 ? q : u;
        std::vector<std::pair<int, double>> moved;  // column (within q or u), step
        for (int n : group) {
          const int dim = part == 0 ? (n < nb_ ? 7 : 1) : udim(n);
          if (d >= dim) continue;
          const int col = (part == 0 ? qcol(n) : ucol(n)) + d;
          const double h = difference_step(x[col]);
          x[col] += h;
          moved.emplace_back(col, h);
        }
        if (moved.empty()) continue;
        s_.set_positions(q.data());
        s_.set_velocities(u.data());
        const Eigen::VectorXd f = s_.applied(t);
        std::size_t k = 0;
        for (int n : group) {
          const int dim = part == 0 ? (n < nb_ ? 7 : 1) : udim(n);
          if (d >= dim) continue;
          const auto [col, h] = moved[k++];
          for (int other : neighbours_[std::size_t(n)])
            for (int r = ucol(other); r < ucol(other) + udim(other); ++r)
              add(nq_ + r, (part == 0 ? 0 : nq_) + col, -(f[r] - f0_[r]) / h);
          x[col] -= h;
        }
      }
}

// d(Phi_v^T lambda)/dq (into the momentum rows) and d(Phi_v u)/dq (into the velocity-constraint
// rows), joint by joint: each of a joint's bodies moved alone, the joint's rows evaluated again.
void GglJacobian::joint_second_derivatives(const double* y) {
  for (const Block& b : blocks_)
    for (int k : b.slots) differenced_joint_block(b, k, y);
}

void GglJacobian::differenced_joint_block(const Block& b, int slot, const double* y) {
  const Eigen::Map<const Eigen::VectorXd> u(y + nq_, nu_), lambda(y + nq_ + nu_, m_);
  RigidBody& moved = s_.bodies[std::size_t(s_.body_in_slot(slot))];
  const RigidBody kept = moved;
  const auto rows_now = [&](std::vector<ConstraintRow>& out) {
    out.clear();
    if (b.joint >= 0) {
      s_.joints[std::size_t(b.joint)].rows(s_.bodies, out);
    } else {
      Row6 shaft_part;
      out.push_back(s_.shaft_bodies[std::size_t(b.shaft_body)].row(s_.bodies, shaft_part));
    }
  };
  std::vector<ConstraintRow> base, now;
  rows_now(base);
  const int vel0 = nq_ + nu_ + mh_ + nb_;
  for (int d = 0; d < 7; ++d) {
    Eigen::Matrix<double, 7, 1> q = Eigen::Map<const Eigen::Matrix<double, 7, 1>>(y + 7 * slot);
    const double h = difference_step(q[d]);
    q[d] += h;
    moved.position = q.head<3>();
    moved.orientation = Quat(q[3], q[4], q[5], q[6]).normalized();
    rows_now(now);
    moved = kept;
    const int col = 7 * slot + d;
    Eigen::Matrix<double, 6, Eigen::Dynamic> stiffness = Eigen::MatrixXd::Zero(6, Eigen::Index(b.slots.size()));
    for (std::size_t r = 0; r < now.size(); ++r) {
      const Row6 di = (now[r].ji - base[r].ji) / h, dj = (now[r].jj - base[r].jj) / h;
      double rate = 0;
      const auto part = [&](int body_index, const Row6& dpart) {
        const int k = s_.slot(body_index);
        if (k < 0) return;
        rate += dpart.dot(u.segment<6>(6 * k));
        const auto at = std::find(b.slots.begin(), b.slots.end(), k) - b.slots.begin();
        stiffness.col(at) += dpart.transpose() * lambda[b.row0 + int(r)];
      };
      part(now[r].i, di);
      part(now[r].j, dj);
      add(vel0 + b.row0 + int(r), col, rate);
    }
    for (std::size_t a = 0; a < b.slots.size(); ++a)
      for (int c = 0; c < 6; ++c) add(nq_ + 6 * b.slots[a] + c, col, stiffness(c, Eigen::Index(a)));
  }
}

}  // namespace terracal::mb
