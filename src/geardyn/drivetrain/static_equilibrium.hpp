#pragma once
// Static equilibrium of a drivetrain under its loads and preloads (docs/theory.md §16.11): the
// residual r(t_0, q, v_0, 0) = 0 with the drivers' and motors' spins held at their angles at
// t_0 and the velocity-dependent terms at the initial rigid spin v_0 (loads at the starting
// speed).
//
// Load control (M. A. Crisfield, "Non-linear Finite Element Analysis of Solids and Structures",
// Vol. 1, 1991, ch. 9, incremental load control): the out-of-balance force at the start,
// P = -r(q_0) (external loads, preloads of bolts, bearings and bushings, drive torques, the
// drivers' offsets), is applied by a load factor s from 0 to 1,
//   r_s(q) = r(q) - (1 - s) r(q_0) = 0,
// which q_0 solves at s = 0 and which is the true equilibrium at s = 1. The increments adapt:
// the first tries the full load (s = 1), a failed increment is halved and restarted from the
// last equilibrium, an easy one (few iterations) doubles the next. Each increment is solved by
// Newton's method on the system's tangent, regularised by mu M (Levenberg-Marquardt: contacts
// that are open have no stiffness, so the plain tangent is singular until they close; mu shrinks
// as the residual falls and the final iterations are plain Newton), with a line search on the
// merit ||r_s||_2^2 whose candidates include the step cut where the first contact switch
// (a tooth flank, gap, roller or bolted joint closing or opening) changes sign.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/drivetrain/drivetrain_system.hpp"
#include "geardyn/fe/dof_map.hpp"

namespace geardyn::drivetrain {

struct StaticOptions {
  double tolerance = 1e-9;              ///< ||r||_inf <= tolerance x (load scale)
  int max_iterations = 1000;            ///< Newton iterations over all increments
  int increment_iterations = 40;        ///< Newton iterations of one increment before it is halved
  double min_increment = 1.0 / 4096.0;  ///< smallest load-factor increment before giving up
  /// Names of the system's equations for the failure message (equation_names(dofs)); empty:
  /// equations by number.
  std::vector<std::string> equation_names;
};

struct StaticResult {
  Status status = Status::Ok;
  std::string message;
  Eigen::VectorXd q;   ///< the equilibrium (on failure: the last equilibrium of the load path)
  int iterations = 0;  ///< Newton iterations over all increments
  int increments = 0;  ///< load increments that converged
  double load_factor = 0.0;          ///< the load factor s reached (1: the full load)
  double residual = 0.0;             ///< ||r||_inf at the end (of the full-load residual)
  double load_scale = 0.0;           ///< the scale of the tolerance [N]
  int worst_equation = -1;           ///< equation of the largest residual on failure
  std::vector<double> held_torques;  ///< torque at each held equation (held_equations order)
};

/// Solves from q (the initial guess) at time t0 with velocity v0. The system is left in
/// dynamic mode.
StaticResult solve_static(DrivetrainSystem& system, double t0, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v0, const StaticOptions& options = {});

/// Names of the equations for messages: "node 'wheel.2' rz", "coordinate 3 of 'housing'".
std::vector<std::string> equation_names(const fe::DofMap& dofs);

/// The unit of an element's force on its relative coordinate `row`: "N m" when the row moves
/// only rotations (a moment), "N" otherwise (a force; a mesh's line of action, whose rotations
/// enter times a lever arm, is a displacement).
std::string coordinate_unit(const PlacedElement& element, Eigen::Index row, const fe::DofMap& dofs);

/// One row of the static_equilibrium table.
struct StaticRow {
  std::string element, quantity, unit;
  double value = 0.0;
};

/// The static_equilibrium table at result.q: every element's force on each of its relative
/// coordinates (unit by coordinate_unit: N for a force, N m for a moment) and the holding torque
/// of every held equation (named by held_names, in held_equations order) in N m.
std::vector<StaticRow> static_table(const DrivetrainSystem& system, const fe::DofMap& dofs,
                                    double t0, const Eigen::VectorXd& v0,
                                    const StaticResult& result,
                                    const std::vector<std::string>& held_names);

}  // namespace geardyn::drivetrain
