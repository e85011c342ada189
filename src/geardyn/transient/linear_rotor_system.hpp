#pragma once
// The linear rotor-bearing model of fe::LinearSystem as a SecondOrderSystem (docs/theory.md §1):
//   M q'' + (C(W) + W(t) G + C_modal) q' + K(W) q = f_unbalance(t)
// with the reference speed W(t) constant or a linear run-up (SpeedProfile), C(W) and K(W)
// including the speed-dependent bearings at W(t) (linear interpolation in the bearing's speed
// table, held constant outside it, as fe::LinearSystem::K_at / C_at), and the modal damping
// C_modal = B diag(c) B^T kept as a low-rank term.
//
// Unbalance (m e at node k with speed ratio r, phase phi): the node spins through
//   theta(t) = r Theta(t),  Theta(t) = integral_0^t W dt,
// and the unbalance sits at angle psi = theta + sign(r) phi from e1 towards e2 of the node frame
// (phi is its angle at t = 0 measured from e1 in the spin sense, the convention of
// fe::unbalance_load). The force it puts on the shaft is minus its mass times its acceleration
// about the node:
//   f_e1 = m e (psi'^2 cos psi + psi'' sin psi),  f_e2 = m e (psi'^2 sin psi - psi'' cos psi),
// with psi' = r W, psi'' = r W': the centrifugal term m e (r W)^2 plus, during a run-up, the
// tangential term m e r W' that lags the rotation. At constant speed this equals
// Re(F exp(i |r| W t)) of fe::unbalance_load.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient {

/// Reference speed over time: W(t) = W0 + (W1 - W0) t / T for 0 <= t <= T, W0 before, W1 after.
struct SpeedProfile {
  double speed_start = 0.0;  ///< W0 [rad/s]
  double speed_end = 0.0;    ///< W1 [rad/s] (= W0 for constant speed)
  double duration = 1.0;     ///< T [s] > 0 (irrelevant for constant speed)

  static SpeedProfile constant(double speed) { return {speed, speed, 1.0}; }
  static SpeedProfile run_up(double from, double to, double duration) {
    return {from, to, duration};
  }
  bool is_constant() const { return speed_start == speed_end; }
  double speed(double t) const;         ///< W(t) [rad/s]
  double acceleration(double t) const;  ///< W'(t) [rad/s^2] ((W1 - W0) / T inside the ramp)
  double angle(double t) const;         ///< Theta(t) = integral_0^t W [rad]
};

/// One unbalance resolved to equations.
struct UnbalanceForce {
  std::string name;
  int node = -1;
  int equation_e1 = -1, equation_e2 = -1;  ///< -1: that DOF is constrained (force to ground)
  double mass_eccentricity = 0.0;          ///< m e [kg m]
  double phase = 0.0;                      ///< phi [rad], in the spin sense
  double speed_ratio = 0.0;                ///< r of the node
};

class LinearRotorSystem final : public SecondOrderSystem {
 public:
  /// Keeps references to `system` (not to `model`). `unbalances` empty: all of the model's.
  /// Throws InputError for an unknown unbalance name or a node the DOF map does not know,
  /// std::invalid_argument for a non-positive or non-finite profile duration or speeds.
  LinearRotorSystem(const model::Model& model, const fe::LinearSystem& system,
                    const SpeedProfile& profile, const std::vector<std::string>& unbalances = {});

  int size() const override { return system_.size(); }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a, Eigen::VectorXd& r) override;
  void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
               double c_k, SparseMatrix& S) override;
  bool tangent_low_rank(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m,
                        double c_c, double c_k, Eigen::MatrixXd& U, Eigen::VectorXd& d) override;
  /// True at constant speed: then K(W), C(W) + W G are constant.
  bool is_linear_time_invariant() const override { return profile_.is_constant(); }

  const SpeedProfile& profile() const { return profile_; }
  const std::vector<UnbalanceForce>& unbalances() const { return unbalances_; }
  /// f_unbalance(t), length n.
  Eigen::VectorXd external_force(double t) const;
  void add_external_force(double t, Eigen::VectorXd& f) const;
  /// Stiffness and damping of the speed-dependent bearings at reference speed W (zero when
  /// there are none), in equation space.
  SparseMatrix bearing_stiffness(double speed) const;
  SparseMatrix bearing_damping(double speed) const;

 private:
  void bearing_blocks(double speed, bool stiffness, std::vector<Eigen::Triplet<double>>& t) const;
  void apply_bearings(double speed, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                      Eigen::VectorXd& r) const;

  const fe::LinearSystem& system_;
  SpeedProfile profile_;
  std::vector<UnbalanceForce> unbalances_;
  bool has_speed_bearings_ = false;
  // Constant speed: K(W) and C(W) + W G assembled once.
  SparseMatrix K_constant_, C_constant_;
  Eigen::VectorXd force_;  // scratch for the residual
};

}  // namespace geardyn::transient
