#pragma once
// The nonlinear drivetrain as a SecondOrderSystem (docs/theory.md §16.9-16.11):
//   r = M a + (C + Omega(v) G) v + K q + C_modal v + sum_e B_e^T f_e(B_e q, B_e v, t)
//       - sum_loads T_L(t, omega) - sum_motors T_m(omega) = 0,
// with the linear rotor, housings and reduced bodies (M, C, K, G of the assembled system, the
// gear meshes left out of it), the placed force elements (placement.hpp), and drivers and loads
// on spin rotations (drivers.hpp).
//
// Kinematics: the spin rotation rz of every node is its total angle (rigid rotation plus
// torsion): the torsional stiffness sees only differences, so large angles are exact for the
// linear shaft model, and gear meshes, bearings and clutches read the actual angles and speeds.
// The gyroscopic matrix G (per unit reference speed) is scaled by the actual reference speed
// Omega(v) = v[speed_equation] / speed_ratio, the spin speed of one node (a driver's) over its
// speed ratio; its derivative with respect to that speed is in the tangent. Speed-dependent
// linear bearings are interpolated at the same Omega(v), their speed derivative in the tangent.
//
// A speed driver's equation is replaced by a stiff, critically damped servo on its tracking
// error e = q_d - theta(t):
//   r_d = M_dd (e'' + 2 omega_s e' + omega_s^2 e),
// which is zero when the driver's angle, speed and acceleration follow the prescribed ones (the
// integrator then reproduces a quadratic theta(t), a constant acceleration, exactly) and pulls
// any discretisation error back at the rate omega_s. The torque the driver applies is the
// residual of its original equation, driver_torque().
//
// Static mode (static_equilibrium.hpp) evaluates the same residual with a = 0 and the drivers'
// and motors' spins held at their angle at t_0 (e = q_d - theta(t_0)).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/drivetrain/drivers.hpp"
#include "geardyn/drivetrain/placement.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::drivetrain {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// An unbalance m e turning with its node's actual spin angle theta (docs/theory.md §16.10): at
/// psi = theta + phi from e1 towards e2 it loads the node with minus its mass times its
/// acceleration about the node, f_e1 = m e (theta'^2 cos psi + theta'' sin psi),
/// f_e2 = m e (theta'^2 sin psi - theta'' cos psi) (as transient::LinearRotorSystem, but with
/// the actual spin instead of the prescribed one).
struct SpinUnbalance {
  std::string name;
  int e1 = -1, e2 = -1;  ///< lateral equations (-1: constrained)
  int spin = -1;         ///< the node's rz equation
  double mass_eccentricity = 0.0;
  double phase = 0.0;
};

/// Everything a DrivetrainSystem is made of, in equation space.
struct DrivetrainParts {
  SparseMatrix M, C, K, G;      ///< G per unit reference speed (may be empty: none)
  Eigen::MatrixXd modal_basis;  ///< C_modal = B diag(c) B^T (may be empty)
  Eigen::VectorXd modal_coefficients;
  /// Bearings whose coefficients depend on speed, evaluated at the actual reference speed
  /// Omega(v) (K and C above leave them out); empty when there is no reference speed.
  std::vector<fe::SpeedDependentBearing> speed_bearings;
  std::vector<PlacedElement> elements;
  std::vector<SpeedDriver> speed_drivers;
  std::vector<Motor> motors;
  std::vector<LoadTorque> loads;
  std::vector<SpinUnbalance> unbalances;
  int speed_equation = -1;   ///< the spin whose speed scales G (-1: G unused)
  double speed_ratio = 1.0;  ///< of that spin
  double servo_frequency = 2.0 * 3.14159265358979323846 * 2000.0;  ///< omega_s [rad/s]
};

class DrivetrainSystem final : public transient::SecondOrderSystem {
 public:
  /// Adds the motors' inertias to M. Throws std::invalid_argument for sizes that do not agree
  /// or an equation out of range.
  explicit DrivetrainSystem(DrivetrainParts parts);

  int size() const override { return static_cast<int>(p_.M.rows()); }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a, Eigen::VectorXd& r) override;
  void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
               double c_k, SparseMatrix& S) override;
  bool tangent_low_rank(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m,
                        double c_c, double c_k, Eigen::MatrixXd& U, Eigen::VectorXd& d) override;
  int num_events() const override { return num_events_; }
  void event_functions(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       Eigen::VectorXd& g) const override;
  std::string describe_event(int k) const override;
  std::string describe_state(double t, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& v) const override;

  /// Static mode: a = 0 and the drivers' and motors' spins held at their angles at t_0.
  void set_static(bool on, double t0 = 0.0) {
    static_ = on;
    static_time_ = t0;
  }
  bool is_static() const { return static_; }

  /// r without the drivers' servo rows (M a + f_int - f_ext); its entry at a driven or held
  /// equation is the torque the driver must apply there.
  void free_residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     const Eigen::VectorXd& a, Eigen::VectorXd& r) const;
  /// Equations whose rows are servo rows (speed drivers; in static mode also motors).
  const std::vector<int>& held_equations() const { return static_ ? held_static_ : held_; }

  /// Internal force of element k at the state (its n coordinates).
  Eigen::VectorXd element_force(std::size_t k, double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const;
  /// The reference speed Omega(v) scaling G [rad/s].
  double reference_speed(const Eigen::VectorXd& v) const;

  const DrivetrainParts& parts() const { return p_; }
  /// Mass matrix with the motors' inertias.
  const SparseMatrix& mass() const { return p_.M; }

 private:
  void add_linear(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                  Eigen::VectorXd& r) const;
  void add_elements(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                    Eigen::VectorXd& r) const;
  void add_loads(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 const Eigen::VectorXd& a, Eigen::VectorXd& r) const;

  DrivetrainParts p_;
  std::vector<int> held_, held_static_;
  std::vector<char> held_row_, held_static_row_;
  std::vector<double> held_mass_;  // M_dd of every equation in held_static_
  int num_events_ = 0;
  std::vector<std::pair<int, int>> event_owner_;  // (element, switch)
  bool static_ = false;
  double static_time_ = 0.0;
};

}  // namespace geardyn::drivetrain
