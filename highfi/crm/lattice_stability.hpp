#pragma once
// Linear stability of the SPH particle lattice under a uniform stress (results/crm_settling,
// "lattice stability"). Perturbing a simple cubic lattice by u e^{ik.x} gives, for the momentum
// equation of the CRM (docs/architecture.md, "CRM") with the Jaumann/elastic stress response,
//   rho u'' = 2 sigma . D(k) u - [(lambda + mu) G G^T + mu |G|^2 I] u,
//   D(k) = sum_l V Hess W(l) (1 - cos k.l),   G(k) = sum_l V sin(k.l) grad W(l),
// over the lattice vectors l within the kernel's support. The first term is the geometric stiffness
// of the stress the particles carry; the second the elastic one, which the SPH velocity gradient
// sees only through G. At the edge of the Brillouin zone G vanishes (the velocity gradient does not
// see a checkerboard), so a compressive stress (sigma < 0) drives any mode with D < 0 unresolved.
// With the Wendland C2 kernel D has such modes at h/d0 = 1.2 and 1.3 (a column mode: columns of
// particles alternating up and down) and none at 1.4: there the lattice is stable under any
// compression.
#include <array>

#include "highfi/crm/sph_kernel.hpp"

namespace terracal {

struct LatticeStability {
  double growth_rate = 0;        // fastest exponential growth [1/s]; 0 when every mode is stable
  std::array<double, 3> wave{};  // its wave vector k d0 / pi (0..1 per axis)
  double min_geometric = 0;      // smallest eigenvalue of d0^2 V D(k) over the zone, or 0 if none is negative
};

// The fastest-growing perturbation of a cubic lattice of spacing d0 carrying the principal stresses
// `stress` (Pa, along x, y, z; compression negative), of density rho and Lame constants lambda, mu,
// sampled on `samples`^3 wave vectors of the irreducible octant of the Brillouin zone.
LatticeStability lattice_stability(KernelType kernel, double h_over_d0, double d0, double rho, double lambda, double mu,
                                   const std::array<double, 3>& stress, int samples = 8);

// omega^2 [1/s^2] as the 3 x 3 matrix of the mode with wave vector
// k = pi k_over_pi / d0: u'' = -omega2 u (a negative eigenvalue is the square of a growth rate).
std::array<std::array<double, 3>, 3> lattice_mode_omega2(KernelType kernel, double h_over_d0, double d0, double rho,
                                                         double lambda, double mu, const std::array<double, 3>& stress,
                                                         const std::array<double, 3>& k_over_pi);

}  // namespace terracal
