#pragma once
// Implicit time integration of a SecondOrderSystem (second_order_system.hpp).
//
// Generalised-alpha (J. Chung, G. M. Hulbert, "A time integration algorithm for structural
// dynamics with improved numerical dissipation: the generalized-alpha method", J. Appl. Mech.
// 60 (1993) 371-375). With n the current step and h the step size it solves, for q_{n+1},
//   r(t_{n+1-af}, q_{n+1-af}, v_{n+1-af}, a_{n+1-am}) = 0,   x_{n+1-a} = (1 - a) x_{n+1} + a x_n
//   q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})
//   v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1})
// with the paper's optimal parameters for a spectral radius at infinite frequency rho_inf in
// [0, 1]:
//   am = (2 rho_inf - 1) / (rho_inf + 1),  af = rho_inf / (rho_inf + 1),
//   gamma = 1/2 - am + af,                 beta = (1 - am + af)^2 / 4.
// It is second-order accurate, unconditionally stable for linear systems, and damps the
// highest frequencies to rho_inf per step while keeping low frequencies nearly undamped.
// The internal force is evaluated at the intermediate point (t_{n+1-af}, q_{n+1-af},
// v_{n+1-af}) with the external force at t_{n+1-af} = (1 - af) t_{n+1} + af t_n; for linear
// systems that is Chung & Hulbert's equation of motion, for nonlinear ones the usual extension.
//
// Newmark average acceleration (the trapezoidal rule): am = af = 0, beta = 1/4, gamma = 1/2.
// Second order, unconditionally stable, no numerical damping; conserves the energy
// 1/2 v^T M v + 1/2 q^T K q of an undamped, unforced linear system exactly.
//
// Each step is solved by Newton's method on the residual in the unknown q_{n+1}, with the
// iteration matrix S = (1 - am) / (beta h^2) M + (1 - af) gamma / (beta h) C_t + (1 - af) K_t.
// * Linear time-invariant systems: S is factorised once for the whole run and each step takes
//   one Newton correction from the predictor, which solves the (linear) step equations exactly.
// * Otherwise (run-up with speed-dependent gyroscopic terms, nonlinear contacts): modified
//   Newton. The factorised S is reused across iterations and steps while the corrections
//   contract fast; when ||dq_k|| / ||dq_{k-1}|| exceeds `refactor_ratio`, S is refactorised at
//   the current iterate. The residual is always evaluated exactly, so a stale S costs
//   iterations, never accuracy.
// The acceleration a_0 is made consistent with the equation of motion, M a_0 = -r(t_0, q_0,
// v_0, 0), unless given.
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient {

enum class Scheme { Newmark, GeneralizedAlpha };

constexpr std::string_view to_string(Scheme s) {
  return s == Scheme::Newmark ? "newmark" : "generalized_alpha";
}

/// The four parameters of the family (Newmark: alpha_m = alpha_f = 0).
struct SchemeParameters {
  double alpha_m = 0.0;
  double alpha_f = 0.0;
  double beta = 0.25;
  double gamma = 0.5;

  /// Average acceleration (trapezoidal rule).
  static SchemeParameters newmark_average_acceleration();
  /// Chung & Hulbert's optimal parameters for rho_infinity (above); throws
  /// std::invalid_argument unless 0 <= rho_infinity <= 1.
  static SchemeParameters generalized_alpha(double rho_infinity);
};

struct IntegratorOptions {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  Scheme scheme = Scheme::GeneralizedAlpha;
  /// Spectral radius at infinite frequency, 0 <= rho_infinity <= 1 (GeneralizedAlpha only):
  /// 1 no numerical damping (= trapezoidal rule), 0 annihilates the highest modes in one step.
  double rho_infinity = 0.9;
  double time_step = kNaN;  ///< h [s], > 0
  int num_steps = 0;        ///< steps to take, >= 1; the run ends at start_time + num_steps h
  double start_time = 0.0;  ///< t_0 [s]

  /// Newton: converged when ||dq||_inf <= newton_tolerance x max(||q||_inf seen so far in the
  /// run, ||q_{n+1}||_inf) (or dq = 0). Not used for linear time-invariant systems (one exact
  /// correction per step).
  double newton_tolerance = 1e-10;
  int max_newton_iterations = 30;  ///< per step, >= 1
  /// Refactorise the iteration matrix when a Newton correction is larger than this fraction of
  /// the previous one (slow contraction of modified Newton), 0 < refactor_ratio < 1.
  double refactor_ratio = 0.1;

  /// Divergence: Status::Diverged when the state has a non-finite entry, or when the state size
  /// s = ||q||_inf + h ||v||_inf + h^2 ||a||_inf grows by more than this factor in one step over
  /// the largest s seen so far (checked once that is non-zero). > 1.
  double max_growth_per_step = 1e3;

  /// Initial acceleration (e.g. to restart a run); empty: consistent, M a_0 = -r(t_0,q_0,v_0,0).
  std::optional<Eigen::VectorXd> initial_acceleration;

  /// Every problem with the options, one message each (empty: valid).
  std::vector<std::string> validate() const;
  SchemeParameters parameters() const;
};

/// What was asked, what was used and what happened (Ceres-style summary).
struct IntegrationSummary {
  Status status = Status::Ok;
  std::string message;  ///< empty when Ok; otherwise what failed, where (step, time), what helps
  Scheme scheme = Scheme::GeneralizedAlpha;
  SchemeParameters parameters;
  double time_step = IntegratorOptions::kNaN;
  int steps_requested = 0;
  int steps_taken = 0;                        ///< accepted steps
  double end_time = IntegratorOptions::kNaN;  ///< time of the last accepted state
  bool linear_time_invariant = false;
  bool consistent_initial_acceleration = true;
  int factorizations = 0;  ///< of the iteration matrix (the mass matrix for a_0 not counted)
  long long newton_iterations = 0;
  long long residual_evaluations = 0;
  int max_iterations_in_step = 0;
  std::string solver;  ///< the factorisation used for the iteration matrix

  /// One line: scheme, steps, factorisations, iterations, status.
  std::string brief_report() const;
};

/// Called with the initial state (step 0) and after every accepted step. `a` is the algorithm's
/// acceleration variable (for generalised-alpha an O(h^2) approximation of q'').
using StepObserver = std::function<void(int step, double t, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& v, const Eigen::VectorXd& a)>;

/// Integrates `system` from (q, v) at options.start_time over options.num_steps steps. On return
/// q and v hold the last accepted state. Throws std::invalid_argument for invalid options or
/// initial vectors of the wrong size. A numerical failure (singular matrix, divergence, Newton
/// not converging) ends the run with that status in the summary; the steps before it were passed
/// to the observer. Reports progress per step.
IntegrationSummary integrate(SecondOrderSystem& system, const IntegratorOptions& options,
                             Eigen::VectorXd& q, Eigen::VectorXd& v, const StepObserver& observer,
                             Progress& progress);

}  // namespace geardyn::transient
