#pragma once
// Modal analysis of a rotor-bearing system at one reference speed (docs/theory.md §1, §3):
//   undamped real modes   K_at(Omega) phi = omega^2 M phi   (no damping, no gyroscopic terms)
//   complex modes         (lambda^2 M + lambda (C_at(Omega) + Omega G + C_modal) + K_at(Omega)) x =
//   0
// Complex modes are reported like ADAMS eigen tables: undamped natural frequency |lambda|/2pi,
// damped frequency |Im lambda|/2pi, damping ratio -Re(lambda)/|lambda|, real and imaginary
// parts; each conjugate pair once, overdamped (real) roots included. Each mode gets a whirl
// direction (forward / backward / none) and a kind (lateral / torsional / axial / coupled).
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/eig/eigen_options.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/eig/rigid_body.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

enum class EigenMethod { Auto, Dense, Sparse };

struct ModalSettings : model::SettingsOf<ModalSettings> {
  double speed = 0.0;  ///< reference speed [rad/s]
  int n_modes = 10;
  bool complex_modes = true;  ///< also the damped gyroscopic (complex) modes
  EigenMethod method = EigenMethod::Auto;
  double shift = 0.0;  ///< shift for shift-invert [rad/s]; modes nearest to it
};

/// Whirl of a lateral mode relative to the spin of the node that moves most laterally.
enum class Whirl { Forward, Backward, None };
/// Dominant DOF family by the mass-weighted energy fractions of fe::mode_families: a family
/// with more than kKindFraction of the energy names the mode, otherwise it is coupled. Solid:
/// the elastic deformation of coupled solids (their modal coordinates) dominates. Rigid: a
/// rigid-body root (see RigidBodyTest), whatever its DOF family.
enum class ModeKind { Lateral, Torsional, Axial, Coupled, Solid, Rigid };
inline constexpr double kKindFraction = 0.8;

constexpr std::string_view to_string(Whirl w) {
  switch (w) {
    case Whirl::Forward:
      return "forward";
    case Whirl::Backward:
      return "backward";
    case Whirl::None:
      return "none";
  }
  return "none";
}
constexpr std::string_view to_string(ModeKind k) {
  switch (k) {
    case ModeKind::Lateral:
      return "lateral";
    case ModeKind::Torsional:
      return "torsional";
    case ModeKind::Axial:
      return "axial";
    case ModeKind::Coupled:
      return "coupled";
    case ModeKind::Solid:
      return "solid";
    case ModeKind::Rigid:
      return "rigid";
  }
  return "coupled";
}

/// One mode, real or complex. An undamped mode has eigenvalue i omega and damping ratio 0.
struct Mode {
  std::complex<double> eigenvalue{eig::kNaN, eig::kNaN};  ///< lambda [rad/s]
  double frequency_hz = eig::kNaN;         ///< |lambda| / 2pi (undamped natural frequency)
  double damped_frequency_hz = eig::kNaN;  ///< |Im lambda| / 2pi
  double damping_ratio = eig::kNaN;        ///< -Re lambda / |lambda|
  bool rigid_body = false;                 ///< a rigid-body root (RigidBodyTest): f = 0
  Whirl whirl = Whirl::None;
  ModeKind kind = ModeKind::Coupled;
  fe::ModeFamilies families;
  double residual = eig::kNaN;  ///< backward error of the eigen-solve
  Eigen::VectorXcd shape;       ///< equation space, largest |entry| = 1
};

struct ModalResult {
  Status status = Status::Failed;
  std::string message;         ///< empty when ok; otherwise what failed and what helps
  double speed = eig::kNaN;    ///< reference speed [rad/s]
  std::vector<Mode> undamped;  ///< ascending frequency
  std::vector<Mode> complex;   ///< ascending |lambda|; empty unless complex modes were asked
  bool complex_requested = true;
  std::string undamped_report;  ///< solver's brief_report()
  std::string complex_report;
  double stiffness_asymmetry = 0;  ///< ||K - K^T|| / ||K||: undamped modes use (K + K^T) / 2
  /// Set when n_modes asked for more modes than the model has: what was returned instead.
  std::string fewer_modes_note;
  double run_time_s = 0;
  /// The modes the tables lead with: complex when computed, else undamped.
  const std::vector<Mode>& primary() const { return complex_requested ? complex : undamped; }
  double max_residual() const;
};

/// Runs the modal analysis on the context's linear system. Throws InputError (located by the
/// context) for invalid settings (n_modes < 1, non-finite speed, negative or non-finite shift);
/// numerical trouble is returned in status / message. settings.shift > 0 [rad/s] asks for the
/// modes nearest that frequency (sigma = shift^2 for the undamped problem, target i shift for
/// the complex one); 0 asks for the lowest modes.
ModalResult run_modal(const model::Model& model, const ModalSettings& settings,
                      const Context& context);

/// Tables "modes", "undamped_modes", "mode_shapes", mode-shape plots along each shaft and notes
/// on how far to trust the result.
AnalysisOutput modal_output(const model::Model& model, const ModalSettings& settings,
                            const ModalResult& result, const Context& context);

/// Logarithmic decrement ln(x_k / x_{k+1}) of successive peaks of a free decay with damping
/// ratio zeta: 2 pi zeta / sqrt(1 - zeta^2) (NaN for |zeta| >= 1: a real root, no oscillation).
/// Negative for a growing oscillation.
double log_decrement(double damping_ratio);

/// A mode counts as unstable when its damping ratio is below -kUnstableDampingRatio. The margin
/// keeps rounding from calling an undamped mode unstable: the eigen-solves give |zeta| up to
/// 2e-6 on undamped rotors of 6000 beam elements. A mode with -1e-5 < zeta < 0 grows by less
/// than 0.01 % per cycle and is reported as neutral (stable "yes").
inline constexpr double kUnstableDampingRatio = 1e-5;
/// True for a mode that grows: not rigid and damping ratio below -kUnstableDampingRatio (an
/// overdamped root with lambda > 0 has damping ratio -1).
bool is_unstable(const Mode& mode);

// ---------------------------------------------------------------------------------------------
// Pieces shared with the Campbell analysis.

/// Maps the model's method choice to the solver's.
eig::Method to_eig_method(EigenMethod method);

/// Whirl of a mode with eigenvalue lambda (Im lambda >= 0) at reference speed `speed`. The orbit
/// of the node with the largest lateral amplitude, x = Re(X e^{i w t}), y = Re(Y e^{i w t}) in
/// the node frame, turns about e3 with sense sign(Im(X conj(Y))) (counter-clockwise > 0, since
/// the mean of x y' - y x' is w Im(X conj(Y))). Forward when that sense equals the node's spin
/// sense sign(speed_ratio) x sign(speed) (speed 0 counts as positive; a node that does not spin
/// is judged against +e3). When no node translates laterally (a disk that only tilts), the orbit
/// of the spin axis' tip (theta_y, -theta_x) at the node that tilts most is used; its sense is
/// Im(theta_x conj(theta_y)). None for real roots, modes with less than 1 % lateral energy and
/// orbits flatter than 1e-4 (|2 Im(X conj(Y))| / (|X|^2 + |Y|^2), 1 for a circle, 0 for a line).
/// `families`: the shape's fe::mode_families when already computed (nullptr: computed here).
Whirl whirl_direction(const fe::LinearSystem& system, const Eigen::VectorXcd& shape,
                      std::complex<double> lambda, double speed,
                      const fe::ModeFamilies* families = nullptr);

ModeKind mode_kind(const fe::ModeFamilies& families);

/// Modal assurance criterion |a^H b|^2 / ((a^H a)(b^H b)) in [0, 1] (R. J. Allemang, D. L. Brown,
/// "A correlation coefficient for modal vector analysis", Proc. 1st International Modal Analysis
/// Conference, 1982).
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);
/// The same with the squared norms a^H a, b^H b already computed (sweeps that score many pairs).
double mac(const Eigen::VectorXcd& a, double a_norm2, const Eigen::VectorXcd& b, double b_norm2);

/// Decides whether a computed root is a rigid-body root, from its shape, not from the size of
/// lambda (whose rounding grows with mesh refinement, see eig/rigid_body.hpp):
///   1. at least kRigidEnergyFraction of the mode's kinetic energy lies in the space of
///      candidate motions that K_at(speed) leaves unstrained; and
///   2. lambda is the zero root of that motion, not another root of it: on an unstrained motion
///      x the quadratic problem reduces to lambda (lambda m + d) = 0, m = x^H M x,
///      d = x^H D x (D = C + Omega G + modal damping), whose other root lambda_d = -d / m is a
///      real physical root (a free rotor on dampers) or the gyroscopic precession of a free
///      rotor's tilt (lambda_d = i Omega I_p / I_d for a disk). The root is rigid when lambda is
///      nearer 0 than lambda_d: |lambda - lambda_d| >= |lambda| / 2.
/// Undamped modes (no D) need only test 1.
struct RigidBodyTest {
  static constexpr double kRigidEnergyFraction = 0.99;
  RigidBodyTest(const fe::LinearSystem& system, double speed,
                const eig::QuadraticPencil* pencil = nullptr);
  bool operator()(std::complex<double> lambda, const Eigen::VectorXcd& shape) const;
  Eigen::Index dimension() const { return space_.dimension(); }

 private:
  const fe::LinearSystem* system_;
  const eig::QuadraticPencil* pencil_;
  eig::RigidBodySpace space_;
};

/// Fills every field of a Mode from lambda and its shape.
Mode describe_mode(const fe::LinearSystem& system, std::complex<double> lambda,
                   const Eigen::VectorXcd& shape, double residual, double speed,
                   const RigidBodyTest& rigid);

}  // namespace geardyn::analyses
