#include "geardyn/transient/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "geardyn/linalg/submatrix.hpp"
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

// Factorises c_m M + c_c C_t + c_k K_t (+ low-rank part) at the given point.
bool factor_tangent(SecondOrderSystem& system, TangentSolver& solver, double t,
                    const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
                    double c_k) {
  SparseMatrix S;
  system.tangent(t, q, v, c_m, c_c, c_k, S);
  Eigen::MatrixXd U;
  Eigen::VectorXd d;
  if (system.tangent_low_rank(t, q, v, c_m, c_c, c_k, U, d) && U.cols() > 0 &&
      d.cwiseAbs().maxCoeff() > 0.0)
    return solver.factorize(S, U, d);
  return solver.factorize(S);
}

}  // namespace

namespace {

void check_input(SecondOrderSystem& system, const IntegratorOptions& options,
                 const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  if (const auto problems = options.validate(); !problems.empty()) {
    std::string text = "invalid integrator options:";
    for (const auto& p : problems) text += " " + p + ";";
    throw std::invalid_argument(text);
  }
  const int n = system.size();
  if (n < 1) throw std::invalid_argument("the system has no unknowns");
  if (q.size() != n || v.size() != n)
    throw std::invalid_argument(fmt::format(
        "initial q and v have sizes {} and {}, the system has {} unknowns", q.size(), v.size(), n));
  if (options.initial_acceleration && options.initial_acceleration->size() != n)
    throw std::invalid_argument(fmt::format("initial acceleration has size {}, expected {}",
                                            options.initial_acceleration->size(), n));
}

struct Failure {
  Status status;
  std::string message;
};

// Equations whose row of M is zero (massless DOFs: the nodes of a massless shaft away from its
// disks), in increasing order.
std::vector<int> massless_equations(const SparseMatrix& M) {
  std::vector<bool> has_mass(static_cast<std::size_t>(M.rows()), false);
  for (int k = 0; k < M.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(M, k); it; ++it)
      if (it.value() != 0.0) {
        has_mass[static_cast<std::size_t>(it.row())] = true;
        has_mass[static_cast<std::size_t>(it.col())] = true;
      }
  std::vector<int> out;
  for (std::size_t i = 0; i < has_mass.size(); ++i)
    if (!has_mass[i]) out.push_back(static_cast<int>(i));
  return out;
}

// The initial acceleration of a system with massless DOFs s (zero rows and columns of M) and
// massed DOFs p: M_pp a_p = -r_p(t_0, q_0, v_0, 0), and the massless DOFs follow the massed ones
// statically (Guyan condensation, differentiated twice in time): K_ss a_s = -K_sp a_p. This is
// exact when the massless DOFs carry no damping and no time-varying load (a massless shaft
// between disks and rigid supports); otherwise a_s is the quasi-static estimate, and it does not
// enter the residual (M a has no a_s term), so the first steps correct it.
std::optional<Failure> partitioned_initial_acceleration(
    SecondOrderSystem& system, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
    const SparseMatrix& M, const std::vector<int>& massless, const Eigen::VectorXd& r,
    Eigen::VectorXd& a) {
  const int n = system.size();
  std::vector<int> massed;
  for (int i = 0, j = 0; i < n; ++i) {
    if (j < static_cast<int>(massless.size()) && massless[static_cast<std::size_t>(j)] == i)
      ++j;
    else
      massed.push_back(i);
  }
  a.setZero(n);
  if (massed.empty())
    return Failure{Status::Singular,
                   fmt::format("initial acceleration at t = {} s: the mass matrix is zero, no DOF "
                               "has mass (give a material a density > 0, or add disks or point "
                               "masses)",
                               t)};
  TangentSolver mass_solver;
  if (!mass_solver.factorize(linalg::submatrix(M, massed, massed)))
    return Failure{Status::Singular,
                   fmt::format("initial acceleration at t = {} s: the mass matrix of the {} DOFs "
                               "that have mass could not be factorised ({}); check for a mass "
                               "or inertia that is zero or negative on a DOF that has some",
                               t, massed.size(), mass_solver.failure())};
  Eigen::VectorXd r_p(static_cast<Eigen::Index>(massed.size())), a_p;
  for (std::size_t i = 0; i < massed.size(); ++i) r_p[static_cast<Eigen::Index>(i)] = r[massed[i]];
  mass_solver.solve(-r_p, a_p);
  SparseMatrix K;
  system.tangent(t, q, v, 0.0, 0.0, 1.0, K);
  TangentSolver stiffness_solver;
  if (!stiffness_solver.factorize(linalg::submatrix(K, massless, massless)))
    return Failure{Status::Singular,
                   fmt::format("initial acceleration at t = {} s: {} DOFs have no mass and their "
                               "stiffness matrix is singular ({}): a massless part of the model "
                               "can move freely (a mechanism without mass or stiffness). Give "
                               "it mass (a density > 0, a disk or point mass), support it "
                               "(bearings, constraints) or leave those DOFs out (`dofs`)",
                               t, massless.size(), stiffness_solver.failure())};
  const Eigen::VectorXd rhs = -(linalg::submatrix(K, massless, massed) * a_p);
  Eigen::VectorXd a_s;
  stiffness_solver.solve(rhs, a_s);
  for (std::size_t i = 0; i < massed.size(); ++i) a[massed[i]] = a_p[static_cast<Eigen::Index>(i)];
  for (std::size_t i = 0; i < massless.size(); ++i)
    a[massless[i]] = a_s[static_cast<Eigen::Index>(i)];
  return std::nullopt;
}

// The initial acceleration: given, or from M a_0 = -r(t_0, q_0, v_0, 0) (partitioned when some
// DOFs have no mass).
std::optional<Failure> initial_acceleration(SecondOrderSystem& system,
                                            const IntegratorOptions& options, double t,
                                            const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                            Eigen::VectorXd& a, IntegrationSummary& summary) {
  const int n = system.size();
  Eigen::VectorXd r(n);
  if (options.initial_acceleration) {
    a = *options.initial_acceleration;
    summary.consistent_initial_acceleration = false;
    return std::nullopt;
  }
  system.residual(t, q, v, Eigen::VectorXd::Zero(n), r);
  ++summary.residual_evaluations;
  // M a_0 = -r(t_0, q_0, v_0, 0): the tangent with c_m = 1, c_c = c_k = 0 is M.
  SparseMatrix M;
  system.tangent(t, q, v, 1.0, 0.0, 0.0, M);
  const std::vector<int> massless = massless_equations(M);
  if (!massless.empty())
    return partitioned_initial_acceleration(system, t, q, v, M, massless, r, a);
  TangentSolver mass_solver;
  if (!factor_tangent(system, mass_solver, t, q, v, 1.0, 0.0, 0.0))
    return Failure{Status::Singular,
                   fmt::format("initial acceleration at t = {} s: the mass matrix could not be "
                               "factorised ({}); every unconstrained DOF needs mass (add rotary "
                               "inertia or a small point mass, or constrain the DOF)",
                               t, mass_solver.failure())};
  mass_solver.solve(-r, a);
  return std::nullopt;
}

// Work vectors of a step: the state at t_{n+1-af}, the residual and the correction.
struct StepWork {
  Eigen::VectorXd qa, va, aa, r, dq;
};

// Newton iterations of one step on (q1, v1, a1) from the predictor.
struct Iterations {
  bool converged = false;
  double previous_correction = 0.0;
  int iteration = 0;
};

// Newton (modified: the factor is kept while the corrections shrink fast enough) on the step
// from (q, v, a) at t_n to (q1, v1, a1) at t1.
std::optional<Failure> newton_iterations(SecondOrderSystem& system,
                                         const IntegratorOptions& options,
                                         const SchemeParameters& p, int step, double t1,
                                         const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& a, Eigen::VectorXd& q1,
                                         Eigen::VectorXd& v1, Eigen::VectorXd& a1, StepWork& w,
                                         TangentSolver& solver, bool& need_factor, double q_scale,
                                         IntegrationSummary& summary, Iterations& it) {
  const double h = options.time_step;
  const double ta = t1 - p.alpha_f * h;  // t_{n+1-af} = (1 - af) t_{n+1} + af t_n
  const double c_m = (1.0 - p.alpha_m) / (p.beta * h * h);
  const double c_c = (1.0 - p.alpha_f) * p.gamma / (p.beta * h);
  const double c_k = 1.0 - p.alpha_f;
  const double dv_dq = p.gamma / (p.beta * h);
  const double da_dq = 1.0 / (p.beta * h * h);
  while (it.iteration < options.max_newton_iterations) {
    w.qa = (1.0 - p.alpha_f) * q1 + p.alpha_f * q;
    w.va = (1.0 - p.alpha_f) * v1 + p.alpha_f * v;
    w.aa = (1.0 - p.alpha_m) * a1 + p.alpha_m * a;
    system.residual(ta, w.qa, w.va, w.aa, w.r);
    ++summary.residual_evaluations;
    if (!w.r.allFinite())
      return Failure{Status::Diverged,
                     fmt::format("non-finite residual at step {} (t = {:.6g} s, h = {:.3g} s); "
                                 "usually the time step is too large for the nonlinearity",
                                 step, t1, h)};
    if (need_factor) {
      if (!factor_tangent(system, solver, ta, w.qa, w.va, c_m, c_c, c_k))
        return Failure{Status::Singular,
                       fmt::format("iteration matrix at step {} (t = {:.6g} s): {}; check for "
                                   "unconstrained rigid-body motion without mass (a massless "
                                   "shaft needs stiffness on every DOF it keeps: bearings, "
                                   "constraints, or `dofs` to leave DOFs out)",
                                   step, t1, solver.failure())};
      ++summary.factorizations;
      summary.solver = solver.description();
      need_factor = false;
    }
    solver.solve(-w.r, w.dq);
    q1 += w.dq;
    v1 += dv_dq * w.dq;
    a1 += da_dq * w.dq;
    ++it.iteration;
    if (summary.linear_time_invariant) {  // exact tangent, linear equations: one correction
      it.converged = true;
      break;
    }
    const double correction = w.dq.lpNorm<Eigen::Infinity>();
    const double scale = std::max(q_scale, q1.lpNorm<Eigen::Infinity>());
    if (correction <= options.newton_tolerance * scale || correction == 0.0) {
      it.converged = true;
      break;
    }
    // Modified Newton: keep the factor while the corrections shrink fast enough.
    if (it.iteration > 1 && correction > options.refactor_ratio * it.previous_correction)
      need_factor = true;
    it.previous_correction = correction;
  }
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
  StepWork w{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n),
             Eigen::VectorXd(n)};
  for (int step = 1; step <= options.num_steps; ++step) {
    const double t1 = options.start_time + step * h;
    // Predictor: constant acceleration.
    a1 = a;
    q1 = q + h * v + (h * h * (0.5 - p.beta)) * a + (h * h * p.beta) * a1;
    v1 = v + (h * (1.0 - p.gamma)) * a + (h * p.gamma) * a1;

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
