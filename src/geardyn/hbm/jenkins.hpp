#pragma once
// Jenkins element (a spring k in series with a Coulomb slider of limit F = mu N, constant N)
// driven by a periodic relative displacement u(theta): the hysteretic tangential force of a
// friction contact in stick and slip (docs/theory.md §8), evaluated over one period for the
// alternating frequency-time method, with its exact derivative with respect to the Fourier
// coefficients of u (an analytic AFT Jacobian).
//
//   stick:  T_j = T_{j-1} + k (u_j - u_{j-1})   while |T_j| < F
//   slip:   T_j = F sign(T_{j-1} + k (u_j - u_{j-1}))
//
// The force is marched over two periods from T = k (u_0 - a_0), clipped to +-F (the element
// stuck about the mean position a_0), and the second period is returned. A loop that slips
// anywhere closes after one period, so the second period is the steady state; a loop that never
// slips is the linear spring k (u - a_0), whose offset the mean position fixes.
// Closed forms for u = X cos theta (Griffin, "Friction damping of resonant stresses in gas
// turbine engine airfoils", J. Eng. Power 102 (1980) 329-333): with beta = arccos(1 - 2F/(kX)),
// X > F/k,
//   equivalent stiffness   k_eq = (k / pi) (beta - sin(2 beta) / 2)
//   equivalent damping     c_eq omega = (4 F / (pi X)) (1 - F / (k X))
//   energy per cycle       W = pi X^2 c_eq omega = 4 F (X - F / k),
// and k_eq = k, W = 0 for X <= F / k (stuck).
#include <Eigen/Dense>

#include "geardyn/hbm/harmonic_basis.hpp"

namespace geardyn::hbm {

struct JenkinsElement {
  double stiffness = 0.0;   ///< k [N/m], > 0
  double slip_force = 0.0;  ///< F = mu N [N], >= 0 (0: no friction force)
};

struct JenkinsResponse {
  Eigen::VectorXd force;         ///< T(theta_j) over the steady period, j = 0 .. n - 1
  Eigen::VectorXd coefficients;  ///< Fourier coefficients of T (HarmonicBasis layout)
  /// d coefficients(T) / d coefficients(u): the AFT Jacobian, size() x size() (empty when not
  /// asked).
  Eigen::MatrixXd jacobian;
  double stick_fraction = 0.0;    ///< share of the samples in stick
  double energy_per_cycle = 0.0;  ///< closed-loop integral of T du over the samples [J]
};

/// The steady periodic force of `element` for the relative displacement with Fourier
/// coefficients `u` in `basis`. Throws InputError for k <= 0 or F < 0. The march carries the
/// force alone; with `with_jacobian` (else `jacobian` is left empty) the Jacobian is built from
/// the stick intervals of the steady period: in stick after the last slip sample a,
/// dT_j/du = k (Q_j - Q_a) (the spring stretched from where the slider stopped), in slip 0, and
/// k (Q_j - e_0) in a loop that never slips (the spring about the mean a_0).
JenkinsResponse jenkins_response(const JenkinsElement& element, const HarmonicBasis& basis,
                                 const Eigen::Ref<const Eigen::VectorXd>& u,
                                 bool with_jacobian = true);

}  // namespace geardyn::hbm
