#pragma once
// Static equilibrium of a drivetrain under its loads and preloads (docs/theory.md §16.11): the
// residual r(t_0, q, v_0, 0) = 0 with the drivers' and motors' spins held at their angles at
// t_0 and the velocity-dependent terms at the initial rigid spin v_0 (loads at the starting
// speed). Newton's method on the system's tangent, regularised by mu M (Levenberg-Marquardt):
// contacts that are open at the start have no stiffness, so the plain tangent is singular until
// they close; mu shrinks as the residual falls and the final iterations are plain Newton.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/drivetrain/drivetrain_system.hpp"

namespace geardyn::drivetrain {

struct StaticOptions {
  double tolerance = 1e-9;  ///< ||r||_inf <= tolerance x (load scale)
  int max_iterations = 200;
};

struct StaticResult {
  Status status = Status::Ok;
  std::string message;
  Eigen::VectorXd q;  ///< the equilibrium
  int iterations = 0;
  double residual = 0.0;             ///< ||r||_inf at the end
  double load_scale = 0.0;           ///< the scale of the tolerance [N]
  std::vector<double> held_torques;  ///< torque at each held equation (held_equations order)
};

/// Solves from q (the initial guess) at time t0 with velocity v0. The system is left in
/// dynamic mode.
StaticResult solve_static(DrivetrainSystem& system, double t0, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v0, const StaticOptions& options = {});

}  // namespace geardyn::drivetrain
