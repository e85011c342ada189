#pragma once
// Nonlinear modes of a structure with nonlinear elements (element_system.hpp) by the extended
// periodic motion concept (EPMC): backbone curves, frequency and damping against amplitude, of
// conservative (hardening springs) and non-conservative (friction) systems.
//
// The EPMC (Krack, "Nonlinear modal analysis of nonconservative systems: extension of the
// periodic motion concept", Computers & Structures 154 (2015) 59-71) defines the nonlinear mode
// of the free, damped system
//   M q'' + C q' + K q + sum_e B_e^T f_e(B_e q, B_e q') = 0
// as the periodic motion of the system with an artificial negative mass-proportional damping
//   M q'' + (C - xi M) q' + K q + sum_e B_e^T f_e = 0,
// xi [1/s] chosen so that it feeds, over a period, the energy that C, the structural loss and the
// elements dissipate. The motion is sought by harmonic balance (harmonic_balance.hpp layout,
// DOF-major X[d (2H+1) + c]) with the unknowns (X, omega, xi) and two more equations:
//   amplitude   X_1^H M X_1 = X_c1^T M X_c1 + X_s1^T M X_s1 = a^2   (X_c1, X_s1: the cosine and
//               sine coefficients of the fundamental of every DOF; a the modal amplitude: for a
//               motion q = a Re(psi e^{i omega t}) of the linear mode psi, psi^H M psi = 1,
//               it is a)
//   phase       Im(psi^H M Q_1) = 0 with Q_1 = X_c1 - i X_s1, i.e.
//               Re(psi)^T M X_s1 + Im(psi)^T M X_c1 = 0 (the projection of the fundamental on
//               the linear mode has zero phase: valid while the nonlinear mode keeps a
//               component along psi; for a real mode phi it is phi^T M X_s1 = 0)
// From each point: the frequency omega, the modal damping ratio zeta = xi / (2 omega) (Krack
// 2015: exact for a linear mode of proportional damping, where xi = 2 zeta_0 omega_0),
// and the energy dissipated per cycle, which the negative damping feeds:
//   W = xi int_0^T q'^T M q' dt = xi pi omega sum_{h=1..H} h^2 (X_ch^T M X_ch + X_sh^T M X_sh).
//
// Solved form (ExtendedPeriodicMotion): the harmonics are scaled by the amplitude, X = a Psi,
// and the force equations divided by a, so the unknowns are of order one at every amplitude:
//   z = (Psi / psi_scale, omega / omega_0, xi / omega_0),   p = log10 a,
// psi_scale the largest |psi_d|, omega_0 the linear natural frequency. The curve is traced by
// the pseudo-arc-length continuation of harmonic_balance.hpp (continue_in_frequency, its
// "frequency" being p) from the linear mode at a small amplitude: Q_1 = a psi, omega = omega_0,
// xi from the linear damping (Newton corrects the guess). The linear mode is a complex mode of
// the linearisation at rest, M q'' + C_lin q' + K_lin q = 0: K plus the elements' tangent
// stiffness at q = 0 (a stuck friction element counts with its stiffness), C plus their tangent
// damping (a regularised friction law at rest is a large damper: its heavily damped DOFs give
// real, overdamped modes, which are not counted, and the oscillatory ones are those of the
// stuck contact) and the structural loss as K_loss / omega_0. From its eigenvalue lambda:
// omega_0 = |lambda|, xi = -2 Re lambda (both exact for proportional damping).
// Where the corrector fails the curve ends there, with the status and the reason.
// References: Krack (2015) above; Krack & Gross, "Harmonic Balance for Nonlinear Vibration
// Problems", Springer (2019), ch. 4 (nonlinear modal analysis); Nayfeh & Mook, "Nonlinear
// Oscillations", Wiley (1979), ch. 4 (the backbone of the Duffing oscillator).
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/hbm/element_system.hpp"

namespace geardyn::hbm {

/// The linear mode a nonlinear mode starts from (the linearisation at rest, see above).
struct LinearModeStart {
  double omega = 0.0;          ///< natural frequency omega_0 [rad/s]
  double xi = 0.0;             ///< the negative damping that makes it periodic [1/s]
  double damping_ratio = 0.0;  ///< xi / (2 omega_0)
  /// psi (n_dof), q = a Re(psi e^{i omega t}); psi^H M psi = 1, its largest entry real > 0
  /// (real for an undamped or proportionally damped mode).
  Eigen::VectorXcd shape;
};

/// The EPMC as a HarmonicSystem for continue_in_frequency: unknowns z (size n_dof (2H+1) + 2,
/// see the header), the continuation parameter p = log10 a in place of the frequency. Rows: the
/// force equations divided by a, then the amplitude and phase conditions times kappa =
/// omega_0^2 ||M psi|| (~ the force per unit amplitude of the linear mode, so that all rows
/// compare).
class ExtendedPeriodicMotion final : public HarmonicSystem {
 public:
  /// `system` without excitation (InputError otherwise), `mode` >= 0 the index of the linear
  /// mode among the oscillatory ones in ascending |lambda| (InputError when out of range).
  ExtendedPeriodicMotion(ElementSystem system, HarmonicBasis basis, int mode);

  int size() const override { return hb_.size() + 2; }
  /// R(z, p); J = dR/dz, dR_domega = dR/dp.
  Eigen::VectorXd residual(const Eigen::VectorXd& z, double p, Eigen::MatrixXd* J = nullptr,
                           Eigen::VectorXd* dR_domega = nullptr) const override;
  /// max(kappa, ||K X|| / a).
  double residual_scale(const Eigen::VectorXd& z, double p) const override;

  const ElementHarmonicBalance& harmonic_balance() const { return hb_; }
  const LinearModeStart& linear_mode() const { return linear_; }
  /// The unknowns of the linear mode (the first guess at any amplitude).
  Eigen::VectorXd linear_guess() const;
  /// Physical harmonics X = a Psi, frequency omega and negative damping xi of unknowns z at
  /// p = log10 a.
  Eigen::VectorXd harmonics(const Eigen::VectorXd& z, double p) const;
  double omega(const Eigen::VectorXd& z) const;
  double xi(const Eigen::VectorXd& z) const;

 private:
  ElementHarmonicBalance hb_;
  LinearModeStart linear_;
  double psi_scale_ = 1.0;
  double kappa_ = 1.0;
  Eigen::VectorXd M_real_, M_imag_;  // M Re psi, M Im psi
  Eigen::MatrixXd G1_;               // xi omega G1_ X: the harmonics of -xi M q'
};

struct NonlinearModeOptions {
  int mode = 0;                   ///< linear mode to start from (0: the lowest)
  double amplitude_start = 1e-3;  ///< modal amplitude a of the first point, > 0
  double amplitude_end = 1.0;     ///< the curve ends at the first point at or past this
  /// Arc-length steps in (z, log10 a): z of order one, so 0.1 is a tenth of a decade of a where
  /// the frequency and the shape change little.
  double step = 0.02;
  double min_step = 1e-7;
  double max_step = 0.1;
  int max_points = 5000;
  double tolerance = 1e-10;  ///< ||R|| <= tolerance * residual_scale per point
  int max_iterations = 20;   ///< Newton iterations per point
};

/// One point of the nonlinear mode.
struct NonlinearModePoint {
  double amplitude = 0.0;         ///< modal amplitude a (sqrt(X_1^H M X_1)) [sqrt(kg) m]
  double omega = 0.0;             ///< frequency [rad/s]
  double xi = 0.0;                ///< negative mass-proportional damping [1/s]
  double damping_ratio = 0.0;     ///< zeta = xi / (2 omega)
  Eigen::VectorXd X;              ///< harmonics, DOF-major (n_dof (2H+1))
  double energy_per_cycle = 0.0;  ///< W = xi pi omega sum h^2 X_h^T M X_h [J]
  /// Energy per cycle of each element's loop (closed-loop integral over its samples) [J].
  Eigen::VectorXd element_energy;
  int iterations = 0;     ///< Newton iterations
  double residual = 0.0;  ///< ||R|| at the converged point
};

struct NonlinearModeResult {
  Status status = Status::Ok;
  std::string message;  ///< empty when ok; otherwise where and why the curve ended
  LinearModeStart linear;
  std::vector<NonlinearModePoint> points;  ///< in the order traced
};

/// Traces the nonlinear mode `options.mode` of `system` (no excitation) in harmonic balance on
/// `basis`, from amplitude_start to amplitude_end. Throws InputError on bad options or system;
/// a continuation that stops early returns its points with status NotConverged and a message.
NonlinearModeResult nonlinear_mode(const ElementSystem& system, const HarmonicBasis& basis,
                                   const NonlinearModeOptions& options);

}  // namespace geardyn::hbm
