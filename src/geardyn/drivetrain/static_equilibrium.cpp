#include "geardyn/drivetrain/static_equilibrium.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/transient/tangent_solver.hpp"

namespace geardyn::drivetrain {
namespace {

/// Restores dynamic mode on every exit path.
struct StaticMode {
  DrivetrainSystem& s;
  StaticMode(DrivetrainSystem& system, double t0) : s(system) { s.set_static(true, t0); }
  ~StaticMode() { s.set_static(false); }
  StaticMode(const StaticMode&) = delete;
  StaticMode& operator=(const StaticMode&) = delete;
};

}  // namespace

StaticResult solve_static(DrivetrainSystem& system, double t0, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v0, const StaticOptions& options) {
  StaticResult out;
  out.q = q;
  const Eigen::Index n = system.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r, dq;
  {
    StaticMode mode(system, t0);
    // Load scale: the external and preload forces at the start (never below 1 N).
    system.residual(t0, out.q, v0, zero, r);
    Eigen::VectorXd free;
    system.free_residual(t0, out.q, v0, zero, free);
    out.load_scale = std::max(1.0, free.cwiseAbs().maxCoeff());
    const SparseMatrix& M = system.mass();
    const double mass_scale = std::max(M.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    double mu = 0.0;
    transient::TangentSolver solver;
    SparseMatrix S;
    for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
      out.residual = r.cwiseAbs().maxCoeff();
      if (!std::isfinite(out.residual)) break;
      if (out.residual <= options.tolerance * out.load_scale) break;
      system.tangent(t0, out.q, v0, 0.0, 0.0, 1.0, S);
      const double k_scale = std::max(S.diagonal().cwiseAbs().maxCoeff(), 1e-300);
      bool stepped = false;
      for (int attempt = 0; attempt < 40 && !stepped; ++attempt) {
        SparseMatrix A = S;
        if (mu > 0.0) A += (mu * k_scale / mass_scale) * M;
        if (!solver.factorize(A)) {
          mu = std::max(mu * 10.0, 1e-8);
          continue;
        }
        solver.solve(-r, dq);
        Eigen::VectorXd trial = out.q + dq, r_trial;
        system.residual(t0, trial, v0, zero, r_trial);
        const double norm = r_trial.cwiseAbs().maxCoeff();
        if (std::isfinite(norm) && norm < out.residual) {
          out.q = trial;
          r = r_trial;
          mu *= 0.1;
          if (mu < 1e-12) mu = 0.0;
          stepped = true;
        } else {
          mu = std::max(mu * 10.0, 1e-8);
        }
      }
      if (!stepped) break;
    }
    out.residual = r.cwiseAbs().maxCoeff();
    system.free_residual(t0, out.q, v0, zero, free);
    for (int e : system.held_equations()) out.held_torques.push_back(free[e]);
  }
  if (!std::isfinite(out.residual)) {
    out.status = Status::Diverged;
    out.message =
        fmt::format("static equilibrium: the residual is not finite after {} iterations; {}",
                    out.iterations, system.describe_state(t0, out.q, v0));
  } else if (out.residual > options.tolerance * out.load_scale) {
    out.status = Status::NotConverged;
    out.message = fmt::format(
        "static equilibrium not reached: |r| = {:.3g} N after {} iterations (tolerance {:.3g} N); "
        "{}. A body held by nothing but open contacts or inactive bolts has no static position: "
        "give it a support, close the contact (gap) or activate the bolt",
        out.residual, out.iterations, options.tolerance * out.load_scale,
        system.describe_state(t0, out.q, v0));
  }
  return out;
}

}  // namespace geardyn::drivetrain
