#pragma once
// Forcing of nonlinear_response by unbalance and base motion, and its continuation over the
// rotor speed (docs/theory.md §19).
//
// Unbalance: an unbalance m e on a node spinning at rho W (rho the node's |speed ratio|, W the
// reference speed) is the rotating force m e (rho W)^2 of fe::unbalance_load, the one of the
// linear `unbalance` analysis, at the frequency rho W. With parameter = "frequency" or
// "force_level" it is a force at the fundamental whose amplitude is frozen at the reference speed
// `speed_rpm` (the selected unbalances must then share one rho). With parameter = "speed" the
// fundamental is w = r W (r = `order`) and an unbalance of ratio rho acts on harmonic rho / r
// (an integer <= H) with the amplitude m e rho^2 W^2 of the current speed.
//
// Base motion: a harmonic motion of the ground, a_g(t) = Re(A e^{i w t}) along a global axis or
// about it (about the axis through the centroid of the model's nodes), given by its acceleration
// amplitude A or its displacement amplitude D (A = -w^2 D). In the coordinates relative to the
// moving ground, u = u_abs - r u_g with r the rigid-body influence vector of the direction, the
// springs, bearings and nonlinear elements to ground act on u and the ground motion enters as the
// effective force f_eff = -M r a_g (Chopra, "Dynamics of Structures", 4th ed., Pearson 2012,
// sec. 1.7 and 9.4). Sensors read the relative motion. The gyroscopic and damping forces of the
// rigid motion are neglected (C r = 0 holds for bearing, spring and stiffness-proportional
// damping; Rayleigh's mass-proportional part and W G r of a rotating base are left out).
// Generalised coordinates of joined bodies take no part in r (exact for Craig-Bampton bodies,
// whose interface nodes carry the rigid motion).
//
// Speed continuation: R(X, W) = R_hb(X, r W; K(W), C(W) + W G) - W^2 F_unb - (r W)^2 F_d - F_0
// traced by the arc-length method over W, with
//   dR/dW = r dR_hb/dw + d/dW [K(W) X + n w (C(W) + W G) X] - 2 W F_unb - 2 r^2 W F_d,
// the structural part from the speed-dependent bearings' analytic slope in their table
// (fe::SpeedDependentBearing::add_speed_derivative: the interpolation is piecewise linear, its
// slope is exact between table speeds) plus d(W G)/dW = G. The modal coordinates (n_modes > 0)
// are the modes at the reference speed, K(W) and C(W) projected on them.
#include <Eigen/Dense>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/nonlinear_elements.hpp"
#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The unbalance and base-motion excitation on the equations, split by how it scales.
struct NonlinearForcing {
  /// n_eq x 3 [a_0, a_1, b_1]: unbalance at the reference speed and base motion at frequency_hz
  /// (frequency, force_level), base acceleration; added to the named forces.
  Eigen::MatrixXd fixed;
  /// n_eq x 3: force per w^2 of a base displacement (frequency, speed).
  Eigen::MatrixXd per_fundamental2;
  /// n_eq x (2 H + 1): unbalance force per W^2 on its harmonic rho / order (speed).
  Eigen::MatrixXd per_speed2;
};

/// The forcing of `settings` (unbalances, base_motion) on `system`; H the balance's harmonics.
/// InputError located by the context: an unbalance on no spinning node, unbalances of several
/// speed ratios at a fixed fundamental, an unbalance whose ratio / order is not a harmonic
/// 1 .. H, a zero reference speed with unbalances at a fixed speed, a base direction along which
/// the model has no DOF.
NonlinearForcing nonlinear_forcing(const model::Model& model, const fe::LinearSystem& system,
                                   const NonlinearResponseSettings& settings, int harmonics,
                                   const Context& context);

/// R(X, p) of nonlinear_response for p the fundamental (parameter = frequency) or the speed
/// (parameter = speed), the structure and the forcing following p (see the header comment).
/// Holds references to `system`, `coordinates` and `reference` (the balance at the reference
/// speed with the fixed excitation): they must outlive it.
class ForcedBalance final : public hbm::HarmonicSystem {
 public:
  ForcedBalance(const fe::LinearSystem& system, const NonlinearCoordinates& coordinates,
                const hbm::ElementHarmonicBalance& reference, const NonlinearForcing& forcing,
                const NonlinearResponseSettings& settings);

  int size() const override { return reference_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double p, Eigen::MatrixXd* J = nullptr,
                           Eigen::VectorXd* dR_dp = nullptr) const override;
  double residual_scale(const Eigen::VectorXd& X, double p) const override;

  /// True when the structure or the forcing changes with p (else this is `reference`).
  bool moves() const { return by_speed_ || Fd_.squaredNorm() > 0.0; }
  /// The fundamental w [rad/s] and the speed W [rad/s] at p.
  double fundamental(double p) const { return by_speed_ ? order_ * p : p; }
  double speed(double p) const { return by_speed_ ? p : speed_; }
  /// The balance with the structure and the excitation at p (solved at fundamental(p)).
  hbm::ElementHarmonicBalance balance_at(double p) const;
  /// The linear response (no elements) at p.
  Eigen::VectorXd linear_response(double p) const;

 private:
  // d/dW [K(W) X + n w (C(W) + W G) X] at fixed w, in the unknowns' layout.
  Eigen::VectorXd structure_speed_derivative(const Eigen::VectorXd& X, double W, double w) const;

  const fe::LinearSystem& system_;
  const NonlinearCoordinates& c_;
  const hbm::ElementHarmonicBalance& reference_;
  Eigen::VectorXd Fd_, Fu_;        ///< per w^2 and per W^2, in the unknowns' layout
  Eigen::MatrixXd modal_damping_;  ///< modal form: the projected modal damping (or empty)
  bool by_speed_ = false;
  double speed_ = 0.0, order_ = 1.0;
};

}  // namespace geardyn::analyses
