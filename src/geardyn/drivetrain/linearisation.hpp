#pragma once
// Linearisation of a drivetrain at an operating point (docs/theory.md §16.12): the tangent
// matrices at the static equilibrium (q*, v_0),
//   M dq'' + C_t dq' + K_t dq = 0,  K_t = d r / d q,  C_t = d r / d v,
// with the held spins (drivers, motors) fixed, and their complex modes by the quadratic
// eigen-solver of the modal analysis (eig::solve_quadratic: shift-invert on the sparse pencil,
// modal damping as its low-rank term; the lowest modes). Contacts enter with
// their tangent stiffness: closed contacts stiffen, open ones add nothing. The modal table is
// the layout of MSC ADAMS' linear analysis: mode, undamped natural frequency |lambda| / 2 pi,
// damping ratio -Re(lambda) / |lambda|, real and imaginary parts of lambda / 2 pi.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/drivetrain/drivetrain_system.hpp"

namespace geardyn::drivetrain {

struct LinearMode {
  std::complex<double> eigenvalue;  ///< lambda [rad/s]
  double natural_frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double real_hz = 0.0, imag_hz = 0.0;  ///< lambda / 2 pi
  Eigen::VectorXcd shape;               ///< displacement part over all equations (held: 0)
  /// With left eigenvectors asked for: y with y^T P(lambda) = 0, P(s) = s^2 M + s D + K_t,
  /// scaled so that y^T P'(lambda) x = 1 (P' = 2 lambda M + D; x = shape), over all equations
  /// (held: 0); the mode's term of the receptance is x y^T / (s - lambda) (docs/theory.md
  /// §16.14). Empty without them.
  Eigen::VectorXcd left;
};

struct Linearisation {
  Status status = Status::Ok;
  std::string message;
  SparseMatrix M, C, K;            ///< over the free equations (C without the low-rank part)
  Eigen::MatrixXd low_rank_basis;  ///< modal damping B (free rows), c below
  Eigen::VectorXd low_rank_coefficients;
  std::vector<int> free;          ///< free equation -> system equation
  int equations = 0;              ///< system equations (free and held)
  std::vector<LinearMode> modes;  ///< Im(lambda) >= 0, sorted by natural frequency; rigid-body
                                  ///< modes (|lambda| below the threshold) left out
  int rigid_body_modes = 0;
  double max_residual = 0.0;  ///< largest backward error of the eigen-solve
  std::string solver;         ///< the eigen-solver's brief report
  int unstable_modes = 0;     ///< Re(lambda) > 0 (beyond round-off)
  bool has_left = false;      ///< every mode has its normalised left eigenvector
  /// Modes whose left eigenvector was not found (the transposed pencil's solve returned no
  /// matching eigenvalue); they have an empty `left`.
  int unmatched_left = 0;
};

/// The tangents at (t, q, v) and the lowest `n_modes` modes (>= 1); with `left`, also their
/// left eigenvectors (a second solve on the transposed pencil), as the modal FRF needs.
Linearisation linearise(DrivetrainSystem& system, double t, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v, int n_modes = 20, bool left = false);

/// The modes of the pencil already in `lin` (M, C, K, the low-rank damping and `free` over a
/// system of `n_equations`): what linearise does after forming the tangents.
void solve_linear_modes(Linearisation& lin, int n_equations, int n_modes, bool left);

}  // namespace geardyn::drivetrain
