#pragma once
// A multibody system in maximal coordinates: bodies, joints and force elements, and the driveline's
// shafts, with the pieces the integrators need: the constraint values and their velocity Jacobian, the
// applied wrenches, the mass, and the packing of positions and velocities into flat vectors. A moving
// body has 7 coordinates (position, unit quaternion w x y z) and 6 velocities (linear world, angular
// body); fixed bodies (the ground) have none; a shaft has its angle and its speed, after the bodies'.
// Joints are position constraints; the shafts' couplings are velocity constraints only.
#include <functional>
#include <type_traits>
#include <vector>

#include "highfi/multibody/force_elements.hpp"
#include "highfi/multibody/joints.hpp"
#include "highfi/multibody/shafts.hpp"

namespace terracal::mb {

class MbSystem {
 public:
  // Forces that are neither gravity nor an element (tires, soil, a driver's push): added to the
  // wrenches at each evaluation, at time t.
  struct ExternalForces {
    using Function = std::function<void(double t, const std::vector<RigidBody>&, std::vector<Wrench>&)>;
    Function apply;
    // The bodies whose state `apply` reads and whose wrenches it writes: the integrator's Jacobian
    // couples only these. Empty: any body (correct, but every body then couples with every other).
    std::vector<int> bodies;
    template <class F>
    requires std::is_invocable_v < F&, double, const std::vector<RigidBody>
    &,
        std::vector<Wrench>& > ExternalForces(F f, std::vector<int> touched = {})
        : apply(std::move(f)),
    bodies(std::move(touched)) {}
  };

  Vec3 gravity{0, 0, -9.81};
  std::vector<RigidBody> bodies;
  std::vector<Joint> joints;
  std::vector<SpringDamper> springs;
  std::vector<RotationalSpringDamper> rotational_springs;
  std::vector<Bushing> bushings;
  std::vector<ExternalForces> external;
  std::vector<Shaft> shafts;
  std::vector<ShaftLinkage> linkages;
  std::vector<ShaftToBody> shaft_bodies;
  std::vector<ShaftTorque> shaft_torques;
  std::vector<Clutch> clutches;
  std::vector<ShaftPairTorque> shaft_pair_torques;

  int add_body(RigidBody b);
  // A joint placed as bodies are now (Joint::place).
  int add_joint(const std::string& name, JointType type, int i, int j, const Vec3& where,
                const Mat3& axes = Mat3::Identity(), const Vec3& other = Vec3::Zero());

  // Call after the last body is added (and again if bodies change from fixed to moving).
  void index();
  int moving() const { return int(moving_.size()); }
  // The moving slot of body b (its block in the velocities), -1 for a fixed body.
  int slot(int b) const { return slot_[std::size_t(b)]; }
  // The body in moving slot k.
  int body_in_slot(int k) const { return moving_[std::size_t(k)]; }
  int velocities() const { return 6 * moving() + int(shafts.size()); }
  int coordinates() const { return 7 * moving() + int(shafts.size()); }
  // Rows of position constraints (the joints') and of all constraints (joints', then the couplings').
  int position_rows() const;
  int constraint_rows() const { return position_rows() + int(linkages.size() + shaft_bodies.size()); }

  void get_positions(double* q) const;  // 7 per moving body, then 1 per shaft
  void set_positions(const double* q);
  void get_velocities(double* u) const;  // 6 per moving body, then 1 per shaft
  void set_velocities(const double* u);
  // d/dt of the coordinates for velocities u: r' = v, quaternion' = q (0, w) / 2.
  void coordinate_rates(const double* q, const double* u, double* qdot) const;

  // The joints' constraint values (position_rows()) and the Jacobian of all constraints against the
  // velocities (constraint_rows() x velocities()).
  void constraints(Eigen::VectorXd& phi, Eigen::MatrixXd& jac) const;
  // The applied wrenches on the moving bodies at time t, minus the gyroscopic term w x J w, and the
  // shafts' torques: the right-hand side of M u' = f - J^T lambda.
  Eigen::VectorXd applied(double t) const;
  // The mass matrix: mass and body-frame inertia per moving body, then the shafts' inertias.
  Eigen::MatrixXd mass_matrix() const;

  // Kinetic energy (bodies and shafts) plus the potential of gravity (springs' energy is not counted).
  double mechanical_energy() const;
  // Moves the positions onto the constraints (least-norm Gauss-Newton) and projects the velocities
  // onto their constraints (least kinetic energy). Throws if the constraints cannot be met or are
  // redundant.
  void assemble(double tolerance = 1e-12, int max_iterations = 50);

 private:
  std::vector<int> moving_;  // body index of each moving body
  std::vector<int> slot_;    // moving slot of each body, -1 for a fixed one
};

}  // namespace terracal::mb
