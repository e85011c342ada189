#pragma once
// geardyn's adaptive generalised-alpha integrator of a SecondOrderSystem (docs/theory.md §16.7):
// the step of integrator.hpp (J. Chung, G. M. Hulbert, "A time integration algorithm for
// structural dynamics with improved numerical dissipation: the generalized-alpha method", 1993)
// with
//   * local error control on q by the estimate e = h^2 (beta - 1/6) (a_{n+1} - a_n)
//     (O. C. Zienkiewicz, Y. M. Xie, "A simple error estimator and adaptive time stepping
//     procedure for dynamic analysis", 1991), step factor clamp(0.9 err^(-1/3), 0.2, 2) with a
//     hysteresis that keeps h (and the factorised iteration matrix) for factors in [1, 1.5];
//   * modified Newton reusing the factorisation across iterations and steps; a step whose Newton
//     iteration fails is retried with h/2;
//   * location of the sign changes of the system's event functions (Illinois secant on the step
//     length), the crossing enclosed in a step of length <= event_tolerance;
//   * output at the fixed sample rate by cubic Hermite interpolation inside the accepted steps.
// The shared options, summary and observer are in adaptive.hpp.
#include <Eigen/Dense>

#include "geardyn/core/progress.hpp"
#include "geardyn/transient/adaptive.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient {

/// Step control of the generalised-alpha integrator that IDA does not share (defaults as in
/// docs/theory.md §16.7).
struct AdaptiveTuning {
  /// Step-size hysteresis: h is kept (and the factorised iteration matrix with it) while the
  /// error controller proposes a growth factor in [1, keep_step_up_to]; 1 disables it.
  double keep_step_up_to = 1.5;
  /// After a located event the next step is this fraction of the step tried before it (the
  /// dynamics on the other side of a contact event are usually faster).
  double restart_fraction = 0.25;
  /// Modified Newton: refactorise when a correction exceeds this fraction of the previous one.
  double refactor_ratio = 0.2;
};

/// The state at t_n + theta h (0 <= theta <= 1) inside an accepted step of length h from
/// (q0, v0, a0) to (q1, v1, a1): q by the cubic Hermite interpolant of (q0, v0, q1, v1), v by its
/// derivative, a linear between a0 and a1. Errors for a smooth solution: O(h^4) in q, O(h^3) in
/// v, O(h^2) in a (on top of the step's own error).
void interpolate_step(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                      const Eigen::VectorXd& a0, const Eigen::VectorXd& q1,
                      const Eigen::VectorXd& v1, const Eigen::VectorXd& a1, double h, double theta,
                      Eigen::VectorXd& q, Eigen::VectorXd& v, Eigen::VectorXd& a);

/// Integrates `system` from (q, v) at options.start_time to options.end_time; the observer gets
/// every output sample (t_0 + k / sample_rate, and t_end) in order, exactly once. On return q and
/// v hold the last accepted state. Invalid options or sizes: std::invalid_argument listing
/// AdaptiveOptions::validate()'s messages. A numerical failure (a step that must go below
/// min_step, a non-finite residual that halving does not cure, a singular iteration matrix,
/// max_steps) ends the run with that status and a message naming the time, the step and
/// system.describe_state(); the samples before it have been delivered. Progress is by time.
AdaptiveSummary integrate_adaptive(SecondOrderSystem& system, const AdaptiveOptions& options,
                                   Eigen::VectorXd& q, Eigen::VectorXd& v,
                                   const SampleObserver& observer, Progress& progress);

/// The same with explicit step-control tuning (measurements of the hysteresis, tests).
AdaptiveSummary integrate_adaptive(SecondOrderSystem& system, const AdaptiveOptions& options,
                                   Eigen::VectorXd& q, Eigen::VectorXd& v,
                                   const SampleObserver& observer, Progress& progress,
                                   const AdaptiveTuning& tuning);

}  // namespace geardyn::transient
