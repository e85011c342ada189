#pragma once
// What the adaptive integrators of a SecondOrderSystem share (docs/theory.md §16.7): the options
// (tolerances, step bounds, the fixed output rate), the summary (steps, rejections, Newton
// iterations, factorisations) and the sample observer. Two integrators implement it so that
// they can be run side by side on the same system:
//   * integrate_adaptive (adaptive_integrator.hpp): geardyn's generalised-alpha with local error
//     control and event location;
//   * integrate_ida (ida_integrator.hpp): SUNDIALS IDA (variable-order BDF) on the first-order
//     form, with geardyn's sparse tangent solver as its linear solver.
// Output is at the fixed sample rate, independent of the steps (interpolated within a step).
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient {

struct AdaptiveOptions {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  double start_time = 0.0;  ///< t_0 [s]
  double end_time = kNaN;   ///< t_end [s] > t_0
  /// Output: samples at t_0 + k / sample_rate for t <= t_end (and t_end itself when it is not a
  /// sample) [Hz] > 0.
  double sample_rate = kNaN;

  /// Local error control: a step is accepted when its error estimate e_i satisfies
  ///   max_i |e_i| / (absolute_tolerance + relative_tolerance |q_i|) <= 1
  /// over the displacement unknowns q (weighted RMS for IDA, as SUNDIALS does).
  double relative_tolerance = 1e-4;
  double absolute_tolerance = 1e-9;  ///< [m, rad] > 0

  double initial_step = kNaN;  ///< [s] (NaN: chosen by the integrator)
  double min_step = 1e-14;     ///< [s] > 0: a step that must go below it is a failure
  double max_step = kNaN;      ///< [s] (NaN: 1 / sample_rate)
  long long max_steps = 50'000'000;

  double rho_infinity = 0.8;  ///< generalised-alpha only, 0 ... 1
  /// Newton (generalised-alpha): converged when ||dq||_inf <= newton_tolerance x the error
  /// weights' scale; a step whose Newton iteration does not converge in max_newton_iterations
  /// is retried with half the step.
  double newton_tolerance = 1e-3;
  int max_newton_iterations = 8;

  /// Locate the sign changes of the system's event functions to within event_tolerance [s]
  /// (generalised-alpha: the step is cut to end just after the event; IDA: its root finding).
  bool locate_events = true;
  double event_tolerance = 1e-9;

  /// Every problem with the options, one message each (empty: valid).
  std::vector<std::string> validate() const;
};

/// What was asked, used and what happened, for both integrators (side-by-side tables).
struct AdaptiveSummary {
  Status status = Status::Ok;
  std::string message;     ///< empty when Ok; else what failed, when (t), and the system's state
  std::string integrator;  ///< "generalized_alpha" or "ida"
  std::string solver;      ///< the linear solver used for the iteration matrix
  long long steps = 0;     ///< accepted steps
  long long rejected_error = 0;   ///< steps rejected by the error test
  long long rejected_newton = 0;  ///< steps rejected because Newton did not converge
  long long newton_iterations = 0;
  long long factorizations = 0;
  long long residual_evaluations = 0;
  long long events = 0;  ///< event-function sign changes located
  double min_step_taken = AdaptiveOptions::kNaN;
  double max_step_taken = AdaptiveOptions::kNaN;
  double end_time = AdaptiveOptions::kNaN;  ///< time of the last accepted state
  long long samples = 0;                    ///< observer calls

  /// One line: integrator, steps, rejections, iterations, factorisations, status.
  std::string brief_report() const;
};

/// Called at every output sample, in time order, with the interpolated state: sample index,
/// time, q, v and a (= q'').
using SampleObserver = std::function<void(long long sample, double t, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, const Eigen::VectorXd& a)>;

}  // namespace geardyn::transient
