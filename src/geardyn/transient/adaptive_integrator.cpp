#include "geardyn/transient/adaptive_integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/transient/generalized_alpha_step.hpp"
#include "geardyn/transient/integrator.hpp"
#include "geardyn/transient/run_input.hpp"
#include "geardyn/transient/tangent_solver.hpp"

namespace geardyn::transient {

namespace {

constexpr double kNaN = AdaptiveOptions::kNaN;

// g crossed zero between g0 and g1 (a value exactly zero at the start is not a crossing: the
// event was located at the end of the previous step).
bool crosses(double g0, double g1) { return (g0 < 0.0 && g1 >= 0.0) || (g0 > 0.0 && g1 <= 0.0); }

int count_crossings(const Eigen::VectorXd& g0, const Eigen::VectorXd& g1) {
  int count = 0;
  for (Eigen::Index k = 0; k < g0.size(); ++k) count += crosses(g0[k], g1[k]) ? 1 : 0;
  return count;
}

void check_input(SecondOrderSystem& system, const AdaptiveOptions& options,
                 const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  detail::check_run_input(system, options.validate(), "invalid adaptive integrator options", q, v);
}

// Why the last attempt of a step failed.
struct AttemptFailure {
  detail::StepOutcome outcome = detail::StepOutcome::Converged;
  int iterations = 0;
  double last_correction = 0.0;
};

class AdaptiveRun {
 public:
  AdaptiveRun(SecondOrderSystem& system, const AdaptiveOptions& options,
              const AdaptiveTuning& tuning, const SampleObserver& observer, Progress& progress,
              Eigen::VectorXd& q, Eigen::VectorXd& v)
      : system_(system),
        o_(options),
        tuning_(tuning),
        observer_(observer),
        progress_(progress),
        p_(SchemeParameters::generalized_alpha(options.rho_infinity)),
        n_(system.size()),
        t_(options.start_time),
        q_(q),
        v_(v),
        a_(Eigen::VectorXd::Zero(n_)),
        w_(n_),
        max_step_(std::isnan(options.max_step) ? 1.0 / options.sample_rate : options.max_step),
        locate_(options.locate_events && system.num_events() > 0) {}

  AdaptiveSummary run();

 private:
  double sample_time(long long k) const;
  void deliver_samples(double t1, double h);
  double initial_step() const;
  double error_norm(double h) const;
  bool attempt(double h, double t1, AttemptFailure& failure);
  void accept(double h, double t1);
  bool locate_event(double h, double& lo, double& hi);
  void evaluate_events(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       Eigen::VectorXd& g) const;
  AdaptiveSummary finish(Status status, std::string message);
  std::string failure_message(const std::string& what, double h) const;

  SecondOrderSystem& system_;
  const AdaptiveOptions& o_;
  const AdaptiveTuning& tuning_;
  const SampleObserver& observer_;
  Progress& progress_;
  SchemeParameters p_;
  int n_;
  double t_;
  Eigen::VectorXd& q_;
  Eigen::VectorXd& v_;
  Eigen::VectorXd a_, q1_, v1_, a1_, q_lo_, v_lo_, a_lo_;
  detail::StepWork w_;
  TangentSolver solver_;
  bool need_factor_ = true;
  double factored_h_ = kNaN;
  detail::NewtonCounters counters_;
  double max_step_;
  bool locate_;
  Eigen::VectorXd g0_, g1_;
  long long next_sample_ = 0, last_regular_sample_ = 0;
  bool end_sample_ = false;  // t_end is not a regular sample: deliver it as one more
  std::string locating_;     // the event being located (for failure messages)
  AdaptiveSummary s_;
};

double AdaptiveRun::sample_time(long long k) const {
  if (k > last_regular_sample_) return o_.end_time;
  return o_.start_time + static_cast<double>(k) / o_.sample_rate;
}

// Samples in (t_, t1] (all remaining ones when t1 is t_end) from the step of length h ending at
// t1: cubic Hermite in (q_n, v_n, q_{n+1}, v_{n+1}) for q, its derivative for v, a linear.
void AdaptiveRun::deliver_samples(double t1, double h) {
  const long long last = last_regular_sample_ + (end_sample_ ? 1 : 0);
  const bool at_end = t1 >= o_.end_time;
  Eigen::VectorXd qs(n_), vs(n_), as(n_);
  while (next_sample_ <= last) {
    const double ts = sample_time(next_sample_);
    if (ts > t1 && !at_end) break;
    interpolate_step(q_, v_, a_, q1_, v1_, a1_, h, std::clamp((ts - t_) / h, 0.0, 1.0), qs, vs, as);
    if (observer_) observer_(next_sample_, ts, qs, vs, as);
    ++next_sample_;
    ++s_.samples;
  }
}

// The first step: given, or one that moves q by about one error weight through the initial
// acceleration, h^2 max_i |a_i| / w_i = 2 (the error estimate of such a step is far below the
// tolerance; the controller grows it by up to 2 per step), at most max_step and (t_end - t_0) /
// 100.
double AdaptiveRun::initial_step() const {
  if (!std::isnan(o_.initial_step)) return std::min(o_.initial_step, max_step_);
  double h = std::min(max_step_, 0.01 * (o_.end_time - o_.start_time));
  double a_norm = 0.0;
  for (int i = 0; i < n_; ++i)
    a_norm = std::max(a_norm, std::abs(a_[i]) / (o_.absolute_tolerance +
                                                 o_.relative_tolerance * std::abs(q_[i])));
  if (a_norm > 0.0) h = std::min(h, std::sqrt(2.0 / a_norm));
  return std::max(h, o_.min_step);
}

// Weighted max norm of Zienkiewicz & Xie's estimate e = h^2 (beta - 1/6) (a_{n+1} - a_n).
double AdaptiveRun::error_norm(double h) const {
  const double c = h * h * (p_.beta - 1.0 / 6.0);
  double err = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double weight =
        o_.absolute_tolerance + o_.relative_tolerance * std::max(std::abs(q_[i]), std::abs(q1_[i]));
    err = std::max(err, std::abs(c * (a1_[i] - a_[i])) / weight);
  }
  return err;
}

// Solves the step of length h from (t_, q_, v_, a_) into (q1_, v1_, a1_). When Newton fails with
// a factorisation from an earlier step, it is retried once with a fresh one.
bool AdaptiveRun::attempt(double h, double t1, AttemptFailure& failure) {
  if (!(h == factored_h_)) need_factor_ = true;
  detail::NewtonControl control;
  control.max_iterations = o_.max_newton_iterations;
  control.refactor_ratio = tuning_.refactor_ratio;
  control.linear = system_.is_linear_time_invariant();
  control.converged = [this](const Eigen::VectorXd& dq, const Eigen::VectorXd& q_new) {
    for (int i = 0; i < n_; ++i)
      if (std::abs(dq[i]) > o_.newton_tolerance * (o_.absolute_tolerance +
                                                   o_.relative_tolerance * std::abs(q_new[i])))
        return false;
    return true;
  };
  const detail::StepCoefficients c(p_, h);
  for (int pass = 0; pass < 2; ++pass) {
    const long long factorizations = counters_.factorizations;
    detail::predict(p_, h, q_, v_, a_, q1_, v1_, a1_);
    const auto result = detail::solve_step(system_, p_, c, t1, q_, v_, a_, q1_, v1_, a1_, w_,
                                           solver_, need_factor_, control, counters_);
    const bool fresh = counters_.factorizations > factorizations;
    if (fresh) factored_h_ = h;
    failure = {result.outcome, result.iterations, result.last_correction};
    if (result.outcome == detail::StepOutcome::Converged) {
      if (q1_.allFinite() && v1_.allFinite() && a1_.allFinite()) return true;
      failure.outcome = detail::StepOutcome::NonFiniteResidual;
      return false;
    }
    if (result.outcome != detail::StepOutcome::NotConverged || fresh) return false;
    need_factor_ = true;  // stale factorisation: once more with a fresh one
  }
  return false;
}

void AdaptiveRun::evaluate_events(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& g) const {
  system_.event_functions(t, q, v, g);
}

// Accepts (q1_, v1_, a1_) at t1 after a step of length h.
void AdaptiveRun::accept(double h, double t1) {
  deliver_samples(t1, h);
  q_.swap(q1_);
  v_.swap(v1_);
  a_.swap(a1_);
  t_ = t1;
  ++s_.steps;
  s_.end_time = t_;
  s_.min_step_taken = s_.steps == 1 ? h : std::min(s_.min_step_taken, h);
  s_.max_step_taken = s_.steps == 1 ? h : std::max(s_.max_step_taken, h);
  system_.commit_step(t_, q_, v_, a_);
  if (locate_) evaluate_events(t_, q_, v_, g0_);
  const double span = o_.end_time - o_.start_time;
  progress_.update(
      static_cast<std::size_t>(std::clamp((t_ - o_.start_time) / span, 0.0, 1.0) * 1000.0));
}

// A step of length h from t_ crossed an event (g1_): brackets the first crossing in step lengths
// lo < hi, hi - lo <= event_tolerance, g (as at t_) unchanged at lo and crossed at hi, by the
// Illinois variant of the secant method on all crossing functions (the earliest estimate wins),
// re-solving the step for each trial length. On return (q_lo_, v_lo_, a_lo_) is the state at
// t_ + lo (when lo > 0). False when a trial step does not converge.
bool AdaptiveRun::locate_event(double h, double& lo, double& hi) {
  lo = 0.0;
  hi = h;
  Eigen::VectorXd g_lo = g0_, g_hi = g1_, g;
  double weight_lo = 1.0, weight_hi = 1.0;
  int kept_lo = 0, kept_hi = 0;  // consecutive trials that kept that end
  AttemptFailure failure;
  for (int iteration = 0; hi - lo > o_.event_tolerance && iteration < 200; ++iteration) {
    double s = hi;
    for (Eigen::Index k = 0; k < g0_.size(); ++k) {
      if (!crosses(g0_[k], g_hi[k])) continue;
      const double gl = weight_lo * g_lo[k], gh = weight_hi * g_hi[k];
      s = std::min(s, gl == gh ? lo : lo + (hi - lo) * gl / (gl - gh));
    }
    if (iteration % 8 == 7) s = 0.5 * (lo + hi);  // guaranteed progress
    const double margin = std::min(0.25 * o_.event_tolerance, 0.25 * (hi - lo));
    s = std::clamp(s, lo + margin, hi - margin);
    if (!attempt(s, t_ + s, failure)) return false;
    evaluate_events(t_ + s, q1_, v1_, g);
    if (count_crossings(g0_, g) > 0) {
      hi = s;
      g_hi = g;
      kept_hi = 0;
      weight_hi = 1.0;
      if (++kept_lo >= 2) weight_lo *= 0.5;
    } else {
      lo = s;
      g_lo = g;
      q_lo_ = q1_;
      v_lo_ = v1_;
      a_lo_ = a1_;
      kept_lo = 0;
      weight_lo = 1.0;
      if (++kept_hi >= 2) weight_hi *= 0.5;
    }
  }
  return true;
}

std::string AdaptiveRun::failure_message(const std::string& what, double h) const {
  std::string state = system_.describe_state(t_, q_, v_);
  return fmt::format(
      "{} at t = {:.9g} s (step h = {:.3g} s, min_step = {:.3g} s, after {} accepted steps{}); "
      "state: {}",
      what, t_, h, o_.min_step, s_.steps,
      locating_.empty() ? "" : ", while locating the event '" + locating_ + "'",
      state.empty() ? "(no diagnosis)" : state);
}

AdaptiveSummary AdaptiveRun::finish(Status status, std::string message) {
  s_.status = status;
  s_.message = std::move(message);
  s_.newton_iterations = counters_.iterations;
  s_.factorizations = counters_.factorizations;
  s_.residual_evaluations = counters_.residual_evaluations;
  s_.solver = counters_.solver;
  progress_.finish();
  return s_;
}

AdaptiveSummary AdaptiveRun::run() {
  s_.integrator = "generalized_alpha";
  s_.end_time = t_;
  const double span = o_.end_time - o_.start_time;
  last_regular_sample_ = static_cast<long long>(std::floor(span * o_.sample_rate * (1 + 1e-12)));
  end_sample_ = o_.end_time - sample_time(last_regular_sample_) > 1e-12 * std::max(span, 1.0);
  progress_.start("adaptive time integration", 1000);
  if (auto failure =
          detail::consistent_acceleration(system_, t_, q_, v_, a_, counters_.residual_evaluations))
    return finish(failure->status, std::move(failure->message));
  if (!q_.allFinite() || !v_.allFinite() || !a_.allFinite())
    return finish(Status::Diverged,
                  fmt::format("the initial state at t = {} s has non-finite entries", t_));
  if (observer_) observer_(0, t_, q_, v_, a_);
  next_sample_ = 1;
  s_.samples = 1;
  if (locate_) evaluate_events(t_, q_, v_, g0_);

  double h = initial_step();
  AttemptFailure failure;
  while (t_ < o_.end_time) {
    if (s_.steps >= o_.max_steps)
      return finish(Status::Failed, failure_message(fmt::format("max_steps = {} reached before "
                                                                "t_end = {} s (raise max_steps or "
                                                                "the tolerances)",
                                                                o_.max_steps, o_.end_time),
                                                    h));
    double h_step = std::min(h, max_step_);
    const bool last = o_.end_time - t_ <= 1.001 * h_step;
    if (last) h_step = o_.end_time - t_;
    const double t1 = last ? o_.end_time : t_ + h_step;
    if (!attempt(h_step, t1, failure)) {
      if (failure.outcome == detail::StepOutcome::Singular)
        return finish(Status::Singular,
                      failure_message(
                          "the iteration matrix is singular (" + solver_.failure() + ")", h_step));
      ++s_.rejected_newton;
      h = 0.5 * h_step;
      if (h < o_.min_step) {
        if (failure.outcome == detail::StepOutcome::NonFiniteResidual)
          return finish(Status::Diverged,
                        failure_message("non-finite residual or state even with the step below "
                                        "min_step",
                                        h));
        return finish(Status::Failed,
                      failure_message(fmt::format("Newton did not converge in {} iterations (last "
                                                  "correction {:.3g}) with the step below min_step",
                                                  failure.iterations, failure.last_correction),
                                      h));
      }
      continue;
    }
    const double err = error_norm(h_step);
    if (err > 1.0) {
      ++s_.rejected_error;
      h = h_step * std::max(0.2, 0.9 * std::pow(err, -1.0 / 3.0));
      if (h < o_.min_step)
        return finish(Status::Failed,
                      failure_message(fmt::format("the local error test failed (error {:.3g} "
                                                  "of the tolerance) with the step below min_step",
                                                  err),
                                      h));
      continue;
    }
    if (locate_) {
      evaluate_events(t1, q1_, v1_, g1_);
      if (count_crossings(g0_, g1_) > 0) {
        double lo = 0.0, hi = 0.0;
        for (Eigen::Index k = 0; k < g0_.size() && locating_.empty(); ++k)
          if (crosses(g0_[k], g1_[k])) locating_ = system_.describe_event(static_cast<int>(k));
        if (!locate_event(h_step, lo, hi)) {
          ++s_.rejected_newton;
          h = 0.5 * h_step;
          if (h < o_.min_step)
            return finish(
                Status::Failed,
                failure_message("Newton did not converge with the step below min_step", h));
          continue;
        }
        if (lo > 0.0) {  // the step to just before the crossing ...
          q1_ = q_lo_;
          v1_ = v_lo_;
          a1_ = a_lo_;
          accept(lo, std::min(t_ + lo, o_.end_time));
        }
        // ... and a step of length <= event_tolerance across it.
        const Eigen::VectorXd g_before = g0_;
        const double h_cross = hi - lo;
        if (!attempt(h_cross, std::min(t_ + h_cross, o_.end_time), failure)) {
          ++s_.rejected_newton;
          h = std::max(0.5 * h_cross, o_.min_step);
          continue;
        }
        accept(h_cross, std::min(t_ + h_cross, o_.end_time));
        s_.events += count_crossings(g_before, g0_);
        locating_.clear();
        h = std::max(tuning_.restart_fraction * h_step, o_.min_step);
        continue;
      }
    }
    locating_.clear();
    accept(h_step, t1);
    double factor = err > 0.0 ? std::clamp(0.9 * std::pow(err, -1.0 / 3.0), 0.2, 2.0) : 2.0;
    if (factor >= 1.0 && factor <= tuning_.keep_step_up_to) factor = 1.0;  // hysteresis
    h = std::min(h_step * factor, max_step_);
    if (last) break;
  }
  return finish(Status::Ok, {});
}

}  // namespace

void interpolate_step(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                      const Eigen::VectorXd& a0, const Eigen::VectorXd& q1,
                      const Eigen::VectorXd& v1, const Eigen::VectorXd& a1, double h, double theta,
                      Eigen::VectorXd& q, Eigen::VectorXd& v, Eigen::VectorXd& a) {
  const double th = theta, th2 = th * th, th3 = th2 * th;
  const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th;
  const double h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
  const double d00 = (6 * th2 - 6 * th) / h, d10 = 3 * th2 - 4 * th + 1;
  const double d01 = (-6 * th2 + 6 * th) / h, d11 = 3 * th2 - 2 * th;
  q = h00 * q0 + (h10 * h) * v0 + h01 * q1 + (h11 * h) * v1;
  v = d00 * q0 + d10 * v0 + d01 * q1 + d11 * v1;
  a = (1.0 - th) * a0 + th * a1;
}

AdaptiveSummary integrate_adaptive(SecondOrderSystem& system, const AdaptiveOptions& options,
                                   Eigen::VectorXd& q, Eigen::VectorXd& v,
                                   const SampleObserver& observer, Progress& progress) {
  return integrate_adaptive(system, options, q, v, observer, progress, AdaptiveTuning{});
}

AdaptiveSummary integrate_adaptive(SecondOrderSystem& system, const AdaptiveOptions& options,
                                   Eigen::VectorXd& q, Eigen::VectorXd& v,
                                   const SampleObserver& observer, Progress& progress,
                                   const AdaptiveTuning& tuning) {
  check_input(system, options, q, v);
  AdaptiveRun run(system, options, tuning, observer, progress, q, v);
  return run.run();
}

}  // namespace geardyn::transient
