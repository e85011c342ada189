#include "geardyn/transient/adaptive.hpp"

#include <fmt/format.h>

#include <cmath>

namespace geardyn::transient {

namespace {

bool positive_finite(double x) { return x > 0.0 && std::isfinite(x); }

}  // namespace

std::vector<std::string> AdaptiveOptions::validate() const {
  std::vector<std::string> problems;
  if (!std::isfinite(start_time))
    problems.push_back(fmt::format("start_time must be finite, got {}", start_time));
  if (!std::isfinite(end_time) || !(end_time > start_time))
    problems.push_back(
        fmt::format("end_time must be finite and > start_time = {}, got {}", start_time, end_time));
  if (!positive_finite(sample_rate))
    problems.push_back(fmt::format("sample_rate must be positive and finite, got {}", sample_rate));
  if (!(relative_tolerance >= 0.0 && relative_tolerance < 1.0))
    problems.push_back(
        fmt::format("relative_tolerance must lie in [0, 1), got {}", relative_tolerance));
  if (!positive_finite(absolute_tolerance))
    problems.push_back(
        fmt::format("absolute_tolerance must be positive and finite, got {}", absolute_tolerance));
  if (!positive_finite(min_step))
    problems.push_back(fmt::format("min_step must be positive and finite, got {}", min_step));
  if (!std::isnan(max_step) && !(positive_finite(max_step) && max_step >= min_step))
    problems.push_back(
        fmt::format("max_step must be NaN (1 / sample_rate) or finite and >= min_step = {}, got {}",
                    min_step, max_step));
  if (!std::isnan(initial_step) && !(positive_finite(initial_step) && initial_step >= min_step))
    problems.push_back(
        fmt::format("initial_step must be NaN (automatic) or finite and >= min_step = {}, got {}",
                    min_step, initial_step));
  if (max_steps < 1) problems.push_back(fmt::format("max_steps must be >= 1, got {}", max_steps));
  if (!(rho_infinity >= 0.0 && rho_infinity <= 1.0))
    problems.push_back(fmt::format("rho_infinity must lie in [0, 1], got {}", rho_infinity));
  if (!positive_finite(newton_tolerance))
    problems.push_back(
        fmt::format("newton_tolerance must be positive and finite, got {}", newton_tolerance));
  if (max_newton_iterations < 1)
    problems.push_back(
        fmt::format("max_newton_iterations must be >= 1, got {}", max_newton_iterations));
  if (locate_events && !positive_finite(event_tolerance))
    problems.push_back(
        fmt::format("event_tolerance must be positive and finite, got {}", event_tolerance));
  return problems;
}

std::string AdaptiveSummary::brief_report() const {
  std::string s = fmt::format(
      "{}{}: {} steps to t={:.9g} s (h {:.3g} .. {:.3g} s), rejected {} (error) + {} (Newton), "
      "{} Newton iteration(s), {} factorisation(s), {} residual(s), {} event(s), {} sample(s), {}",
      integrator.empty() ? "integrator" : integrator, solver.empty() ? "" : " [" + solver + "]",
      steps, end_time, min_step_taken, max_step_taken, rejected_error, rejected_newton,
      newton_iterations, factorizations, residual_evaluations, events, samples, to_string(status));
  if (!message.empty()) s += ": " + message;
  return s;
}

}  // namespace geardyn::transient
