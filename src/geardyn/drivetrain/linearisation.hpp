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
};

struct Linearisation {
  Status status = Status::Ok;
  std::string message;
  SparseMatrix M, C, K;            ///< over the free equations (C without the low-rank part)
  Eigen::MatrixXd low_rank_basis;  ///< modal damping B (free rows), c below
  Eigen::VectorXd low_rank_coefficients;
  std::vector<int> free;          ///< free equation -> system equation
  std::vector<LinearMode> modes;  ///< Im(lambda) >= 0, sorted by natural frequency; rigid-body
                                  ///< modes (|lambda| below the threshold) left out
  int rigid_body_modes = 0;
  double max_residual = 0.0;  ///< largest backward error of the eigen-solve
  std::string solver;         ///< the eigen-solver's brief report
  int unstable_modes = 0;     ///< Re(lambda) > 0 (beyond round-off)
};

/// The tangents at (t, q, v) and the lowest `n_modes` modes (>= 1).
Linearisation linearise(DrivetrainSystem& system, double t, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v, int n_modes = 20);

}  // namespace geardyn::drivetrain
