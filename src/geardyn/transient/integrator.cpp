#include "geardyn/transient/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "geardyn/transient/generalized_alpha_step.hpp"
#include "geardyn/transient/run_input.hpp"
#include "geardyn/transient/tangent_solver.hpp"

namespace geardyn::transient {

SchemeParameters SchemeParameters::newmark_average_acceleration() { return {0.0, 0.0, 0.25, 0.5}; }

SchemeParameters SchemeParameters::generalized_alpha(double rho_infinity) {
  if (!(rho_infinity >= 0.0 && rho_infinity <= 1.0))
    throw std::invalid_argument(
        fmt::format("rho_infinity must lie in [0, 1], got {}", rho_infinity));
  SchemeParameters p;
  p.alpha_m = (2.0 * rho_infinity - 1.0) / (rho_infinity + 1.0);
  p.alpha_f = rho_infinity / (rho_infinity + 1.0);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  const double s = 1.0 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * s * s;
  return p;
}

std::vector<std::string> IntegratorOptions::validate() const {
  std::vector<std::string> problems;
  if (scheme == Scheme::GeneralizedAlpha && !(rho_infinity >= 0.0 && rho_infinity <= 1.0))
    problems.push_back(fmt::format("rho_infinity must lie in [0, 1], got {}", rho_infinity));
  if (!(time_step > 0.0) || !std::isfinite(time_step))
    problems.push_back(fmt::format("time_step must be positive and finite, got {}", time_step));
  if (num_steps < 1) problems.push_back(fmt::format("num_steps must be >= 1, got {}", num_steps));
  if (!std::isfinite(start_time))
    problems.push_back(fmt::format("start_time must be finite, got {}", start_time));
  if (!(newton_tolerance > 0.0 && newton_tolerance < 1.0))
    problems.push_back(
        fmt::format("newton_tolerance must lie in (0, 1), got {}", newton_tolerance));
  if (max_newton_iterations < 1)
    problems.push_back(
        fmt::format("max_newton_iterations must be >= 1, got {}", max_newton_iterations));
  if (!(refactor_ratio > 0.0 && refactor_ratio < 1.0))
    problems.push_back(fmt::format("refactor_ratio must lie in (0, 1), got {}", refactor_ratio));
  if (!(max_growth_per_step > 1.0))
    problems.push_back(fmt::format("max_growth_per_step must be > 1, got {}", max_growth_per_step));
  return problems;
}

SchemeParameters IntegratorOptions::parameters() const {
  return scheme == Scheme::Newmark ? SchemeParameters::newmark_average_acceleration()
                                   : SchemeParameters::generalized_alpha(rho_infinity);
}

std::string IntegrationSummary::brief_report() const {
  std::string s = fmt::format(
      "{} (am={:.4g}, af={:.4g}, beta={:.4g}, gamma={:.4g}), h={:.4g} s: {}/{} steps to "
      "t={:.6g} s, {} factorisation(s), {} Newton iteration(s) (max {} per step), {}",
      to_string(scheme), parameters.alpha_m, parameters.alpha_f, parameters.beta, parameters.gamma,
      time_step, steps_taken, steps_requested, end_time, factorizations, newton_iterations,
      max_iterations_in_step, to_string(status));
  if (!message.empty()) s += ": " + message;
  return s;
}

namespace {

double state_size(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                  double h) {
  return q.lpNorm<Eigen::Infinity>() + h * v.lpNorm<Eigen::Infinity>() +
         h * h * a.lpNorm<Eigen::Infinity>();
}

bool all_finite(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
  return q.allFinite() && v.allFinite() && a.allFinite();
}

using detail::Failure;
using detail::StepWork;

void check_input(SecondOrderSystem& system, const IntegratorOptions& options,
                 const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  detail::check_run_input(system, options.validate(), "invalid integrator options", q, v);
  const int n = system.size();
  if (options.initial_acceleration && options.initial_acceleration->size() != n)
    throw std::invalid_argument(fmt::format("initial acceleration has size {}, expected {}",
                                            options.initial_acceleration->size(), n));
}

// The initial acceleration: given, or from M a_0 = -r(t_0, q_0, v_0, 0) (partitioned when some
// DOFs have no mass).
std::optional<Failure> initial_acceleration(SecondOrderSystem& system,
                                            const IntegratorOptions& options, double t,
                                            const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                            Eigen::VectorXd& a, IntegrationSummary& summary) {
  if (options.initial_acceleration) {
    a = *options.initial_acceleration;
    summary.consistent_initial_acceleration = false;
    return std::nullopt;
  }
  return detail::consistent_acceleration(system, t, q, v, a, summary.residual_evaluations);
}

// Newton iterations of one step on (q1, v1, a1) from the predictor.
struct Iterations {
  bool converged = false;
  double previous_correction = 0.0;
  int iteration = 0;
};

// Newton (modified: the factor is kept while the corrections shrink fast enough) on the step
// from (q, v, a) at t_n to (q1, v1, a1) at t1 (detail::solve_step), with this integrator's
// convergence test and messages.
std::optional<Failure> newton_iterations(SecondOrderSystem& system,
                                         const IntegratorOptions& options,
                                         const SchemeParameters& p, int step, double t1,
                                         const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& a, Eigen::VectorXd& q1,
                                         Eigen::VectorXd& v1, Eigen::VectorXd& a1, StepWork& w,
                                         TangentSolver& solver, bool& need_factor, double q_scale,
                                         IntegrationSummary& summary, Iterations& it) {
  const double h = options.time_step;
  detail::NewtonControl control;
  control.max_iterations = options.max_newton_iterations;
  control.refactor_ratio = options.refactor_ratio;
  control.linear = summary.linear_time_invariant;
  control.converged = [&](const Eigen::VectorXd& dq, const Eigen::VectorXd& q_new) {
    const double scale = std::max(q_scale, q_new.lpNorm<Eigen::Infinity>());
    return dq.lpNorm<Eigen::Infinity>() <= options.newton_tolerance * scale;
  };
  detail::NewtonCounters counters;
  const auto result = detail::solve_step(system, p, detail::StepCoefficients(p, h), t1, q, v, a, q1,
                                         v1, a1, w, solver, need_factor, control, counters);
  summary.residual_evaluations += counters.residual_evaluations;
  summary.factorizations += static_cast<int>(counters.factorizations);
  if (!counters.solver.empty()) summary.solver = counters.solver;
  it.iteration = result.iterations;
  it.previous_correction = result.last_correction;
  it.converged = result.outcome == detail::StepOutcome::Converged;
  if (result.outcome == detail::StepOutcome::NonFiniteResidual)
    return Failure{Status::Diverged,
                   fmt::format("non-finite residual at step {} (t = {:.6g} s, h = {:.3g} s); "
                               "usually the time step is too large for the nonlinearity",
                               step, t1, h)};
  if (result.outcome == detail::StepOutcome::Singular)
    return Failure{Status::Singular,
                   fmt::format("iteration matrix at step {} (t = {:.6g} s): {}; check for "
                               "unconstrained rigid-body motion without mass (a massless "
                               "shaft needs stiffness on every DOF it keeps: bearings, "
                               "constraints, or `dofs` to leave DOFs out)",
                               step, t1, result.solver_failure)};
  return std::nullopt;
}

}  // namespace

IntegrationSummary integrate(SecondOrderSystem& system, const IntegratorOptions& options,
                             Eigen::VectorXd& q, Eigen::VectorXd& v, const StepObserver& observer,
                             Progress& progress) {
  check_input(system, options, q, v);
  const int n = system.size();

  const SchemeParameters p = options.parameters();
  const double h = options.time_step;
  IntegrationSummary summary;
  summary.scheme = options.scheme;
  summary.parameters = p;
  summary.time_step = h;
  summary.steps_requested = options.num_steps;
  summary.end_time = options.start_time;
  summary.linear_time_invariant = system.is_linear_time_invariant();

  auto fail = [&](Status status, std::string message) {
    summary.status = status;
    summary.message = std::move(message);
    progress.finish();
    return summary;
  };

  double t = options.start_time;
  Eigen::VectorXd a(n);
  progress.start("time integration", static_cast<std::size_t>(options.num_steps));

  if (auto failure = initial_acceleration(system, options, t, q, v, a, summary))
    return fail(failure->status, std::move(failure->message));
  if (!all_finite(q, v, a))
    return fail(Status::Diverged,
                fmt::format("the initial state at t = {} s has non-finite entries", t));
  if (observer) observer(0, t, q, v, a);

  TangentSolver solver;
  bool need_factor = true;
  double q_scale = q.lpNorm<Eigen::Infinity>();
  double largest_state = state_size(q, v, a, h);

  Eigen::VectorXd q1(n), v1(n), a1(n);
  StepWork w(n);
  for (int step = 1; step <= options.num_steps; ++step) {
    const double t1 = options.start_time + step * h;
    detail::predict(p, h, q, v, a, q1, v1, a1);  // constant acceleration

    Iterations it;
    if (auto failure = newton_iterations(system, options, p, step, t1, q, v, a, q1, v1, a1, w,
                                         solver, need_factor, q_scale, summary, it))
      return fail(failure->status, std::move(failure->message));
    const int iteration = it.iteration;
    const double previous_correction = it.previous_correction;
    const bool converged = it.converged;
    summary.newton_iterations += iteration;
    summary.max_iterations_in_step = std::max(summary.max_iterations_in_step, iteration);
    if (!converged)
      return fail(Status::NotConverged,
                  fmt::format("Newton did not converge at step {} (t = {:.6g} s) in {} "
                              "iterations (last correction {:.3g}, tolerance {:.3g}); reduce "
                              "the time step or raise max_newton_iterations",
                              step, t1, iteration, previous_correction,
                              options.newton_tolerance * std::max(q_scale, q1.norm())));
    if (!all_finite(q1, v1, a1))
      return fail(
          Status::Diverged,
          fmt::format("non-finite state at step {} (t = {:.6g} s, h = {:.3g} s)", step, t1, h));
    const double size = state_size(q1, v1, a1, h);
    if (largest_state > 0.0 && size > options.max_growth_per_step * largest_state)
      return fail(Status::Diverged,
                  fmt::format("the state grew by a factor {:.3g} in one step at step {} "
                              "(t = {:.6g} s, h = {:.3g} s); usually the time step is too large "
                              "for the nonlinearity",
                              size / largest_state, step, t1, h));
    largest_state = std::max(largest_state, size);
    q_scale = std::max(q_scale, q1.lpNorm<Eigen::Infinity>());

    q.swap(q1);
    v.swap(v1);
    a.swap(a1);
    t = t1;
    summary.steps_taken = step;
    summary.end_time = t;
    system.commit_step(t, q, v, a);
    if (observer) observer(step, t, q, v, a);
    progress.update(static_cast<std::size_t>(step));
  }
  progress.finish();
  return summary;
}

}  // namespace geardyn::transient
