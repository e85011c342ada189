#pragma once
// One generalised-alpha step, written once for the fixed-step integrator (integrator.hpp) and the
// adaptive one (adaptive_integrator.hpp): the predictor, Newton's iteration on q_{n+1} with a
// reusable factorised iteration matrix, and the consistent initial acceleration. Internal to the
// transient module; the equations are in integrator.hpp and docs/theory.md §16.7.
#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>

#include "geardyn/core/status.hpp"
#include "geardyn/transient/integrator.hpp"
#include "geardyn/transient/second_order_system.hpp"
#include "geardyn/transient/tangent_solver.hpp"

namespace geardyn::transient::detail {

struct Failure {
  Status status;
  std::string message;
};

/// The step's constants for step size h: iteration matrix S = c_m M + c_c C_t + c_k K_t and the
/// derivatives of v_{n+1}, a_{n+1} with respect to q_{n+1}.
struct StepCoefficients {
  StepCoefficients(const SchemeParameters& p, double h);
  double h, c_m, c_c, c_k, dv_dq, da_dq;
};

/// Work vectors of a step: the state at t_{n+1-af}, the residual and the correction.
struct StepWork {
  explicit StepWork(int n);
  Eigen::VectorXd qa, va, aa, r, dq;
};

/// How Newton's iteration stops.
struct NewtonControl {
  int max_iterations = 1;
  /// Refactorise when a correction exceeds this fraction of the previous one.
  double refactor_ratio = 0.1;
  /// Linear time-invariant system: one correction solves the step exactly.
  bool linear = false;
  /// Convergence test on the correction dq and the updated q_{n+1}.
  std::function<bool(const Eigen::VectorXd& dq, const Eigen::VectorXd& q1)> converged;
};

/// Counters accumulated over a run.
struct NewtonCounters {
  long long residual_evaluations = 0;
  long long factorizations = 0;
  long long iterations = 0;
  std::string solver;  ///< the last factorisation's description
};

enum class StepOutcome { Converged, NotConverged, NonFiniteResidual, Singular };

struct StepResult {
  StepOutcome outcome = StepOutcome::NotConverged;
  int iterations = 0;
  double last_correction = 0.0;  ///< ||dq||_inf of the last correction
  std::string solver_failure;    ///< Singular: the solver's explanation
};

/// Factorises c_m M + c_c C_t + c_k K_t (+ the low-rank part) at (t, q, v).
bool factor_tangent(SecondOrderSystem& system, TangentSolver& solver, double t,
                    const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
                    double c_k);

/// Constant-acceleration predictor of the step from (q, v, a): a1 = a, q1, v1 from the update
/// formulas.
void predict(const SchemeParameters& p, double h, const Eigen::VectorXd& q,
             const Eigen::VectorXd& v, const Eigen::VectorXd& a, Eigen::VectorXd& q1,
             Eigen::VectorXd& v1, Eigen::VectorXd& a1);

/// Newton on the step from (q, v, a) at t1 - h to (q1, v1, a1) at t1, starting from the values
/// in q1, v1, a1 (the predictor). Modified Newton: the factor in `solver` is reused while
/// `need_factor` is false and the corrections shrink by at least refactor_ratio; it is
/// refactorised at the current iterate otherwise. The residual is checked for finiteness before
/// it is used.
StepResult solve_step(SecondOrderSystem& system, const SchemeParameters& p,
                      const StepCoefficients& c, double t1, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& v, const Eigen::VectorXd& a, Eigen::VectorXd& q1,
                      Eigen::VectorXd& v1, Eigen::VectorXd& a1, StepWork& w, TangentSolver& solver,
                      bool& need_factor, const NewtonControl& control, NewtonCounters& counters);

/// The consistent initial acceleration M a_0 = -r(t_0, q_0, v_0, 0), partitioned when some DOFs
/// have no mass (see generalized_alpha_step.cpp). Counts its residual evaluation.
std::optional<Failure> consistent_acceleration(SecondOrderSystem& system, double t,
                                               const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                               Eigen::VectorXd& a, long long& residual_evaluations);

}  // namespace geardyn::transient::detail
