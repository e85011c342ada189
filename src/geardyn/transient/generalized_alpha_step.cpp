#include "geardyn/transient/generalized_alpha_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "geardyn/linalg/submatrix.hpp"

namespace geardyn::transient::detail {

StepCoefficients::StepCoefficients(const SchemeParameters& p, double step)
    : h(step),
      c_m((1.0 - p.alpha_m) / (p.beta * step * step)),
      c_c((1.0 - p.alpha_f) * p.gamma / (p.beta * step)),
      c_k(1.0 - p.alpha_f),
      dv_dq(p.gamma / (p.beta * step)),
      da_dq(1.0 / (p.beta * step * step)) {}

StepWork::StepWork(int n)
    : qa(Eigen::VectorXd::Zero(n)),
      va(Eigen::VectorXd::Zero(n)),
      aa(Eigen::VectorXd::Zero(n)),
      r(Eigen::VectorXd::Zero(n)),
      dq(Eigen::VectorXd::Zero(n)) {}

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

void predict(const SchemeParameters& p, double h, const Eigen::VectorXd& q,
             const Eigen::VectorXd& v, const Eigen::VectorXd& a, Eigen::VectorXd& q1,
             Eigen::VectorXd& v1, Eigen::VectorXd& a1) {
  a1 = a;
  q1 = q + h * v + (h * h * (0.5 - p.beta)) * a + (h * h * p.beta) * a1;
  v1 = v + (h * (1.0 - p.gamma)) * a + (h * p.gamma) * a1;
}

StepResult solve_step(SecondOrderSystem& system, const SchemeParameters& p,
                      const StepCoefficients& c, double t1, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& v, const Eigen::VectorXd& a, Eigen::VectorXd& q1,
                      Eigen::VectorXd& v1, Eigen::VectorXd& a1, StepWork& w, TangentSolver& solver,
                      bool& need_factor, const NewtonControl& control, NewtonCounters& counters) {
  const double ta = t1 - p.alpha_f * c.h;  // t_{n+1-af} = (1 - af) t_{n+1} + af t_n
  StepResult result;
  double previous_correction = 0.0;
  while (result.iterations < control.max_iterations) {
    w.qa = (1.0 - p.alpha_f) * q1 + p.alpha_f * q;
    w.va = (1.0 - p.alpha_f) * v1 + p.alpha_f * v;
    w.aa = (1.0 - p.alpha_m) * a1 + p.alpha_m * a;
    system.residual(ta, w.qa, w.va, w.aa, w.r);
    ++counters.residual_evaluations;
    if (!w.r.allFinite()) {
      result.outcome = StepOutcome::NonFiniteResidual;
      return result;
    }
    if (need_factor) {
      if (!factor_tangent(system, solver, ta, w.qa, w.va, c.c_m, c.c_c, c.c_k)) {
        result.outcome = StepOutcome::Singular;
        result.solver_failure = solver.failure();
        return result;
      }
      ++counters.factorizations;
      counters.solver = solver.description();
      need_factor = false;
    }
    solver.solve(-w.r, w.dq);
    q1 += w.dq;
    v1 += c.dv_dq * w.dq;
    a1 += c.da_dq * w.dq;
    ++result.iterations;
    ++counters.iterations;
    if (control.linear) {  // exact tangent, linear equations: one correction
      result.outcome = StepOutcome::Converged;
      return result;
    }
    const double correction = w.dq.lpNorm<Eigen::Infinity>();
    result.last_correction = correction;
    if (correction == 0.0 || control.converged(w.dq, q1)) {
      result.outcome = StepOutcome::Converged;
      return result;
    }
    // Modified Newton: keep the factor while the corrections shrink fast enough.
    if (result.iterations > 1 && correction > control.refactor_ratio * previous_correction)
      need_factor = true;
    previous_correction = correction;
  }
  result.outcome = StepOutcome::NotConverged;
  return result;
}

namespace {

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

}  // namespace

std::optional<Failure> consistent_acceleration(SecondOrderSystem& system, double t,
                                               const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                               Eigen::VectorXd& a,
                                               long long& residual_evaluations) {
  const int n = system.size();
  Eigen::VectorXd r(n);
  system.residual(t, q, v, Eigen::VectorXd::Zero(n), r);
  ++residual_evaluations;
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

}  // namespace geardyn::transient::detail
