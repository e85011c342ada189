#include "geardyn/drivetrain/static_equilibrium.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

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

/// The load-controlled residual r_s(q) = r(q) - (1 - s) r(q_0) and its Newton solver.
class LoadPath {
 public:
  LoadPath(DrivetrainSystem& system, double t0, const Eigen::VectorXd& q0,
           const Eigen::VectorXd& v0)
      : sys_(system), t0_(t0), v0_(v0), zero_(Eigen::VectorXd::Zero(system.size())) {
    sys_.residual(t0_, q0, v0_, zero_, r0_);
    const SparseMatrix& M = sys_.mass();
    mass_scale_ = std::max(M.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  }

  void residual(double s, const Eigen::VectorXd& q, Eigen::VectorXd& r) const {
    sys_.residual(t0_, q, v0_, zero_, r);
    if (s != 1.0) r -= (1.0 - s) * r0_;
  }

  struct Outcome {
    bool converged = false;
    int iterations = 0;
    Eigen::VectorXd r;  ///< r_s at the last iterate
  };

  /// Newton-LM at load factor s from q (updated in place) to ||r_s||_inf <= tol.
  Outcome solve(double s, Eigen::VectorXd& q, double tol, int max_iterations) {
    Outcome out;
    Eigen::VectorXd& r = out.r;
    Eigen::VectorXd dq, trial, r_trial;
    residual(s, q, r);
    double mu = 0.0;
    SparseMatrix S;
    for (;; ++out.iterations) {
      const double norm = r.cwiseAbs().maxCoeff();
      if (!std::isfinite(norm)) return out;
      if (norm <= tol) {
        out.converged = true;
        return out;
      }
      if (out.iterations >= max_iterations) return out;
      sys_.tangent(t0_, q, v0_, 0.0, 0.0, 1.0, S);
      const double k_scale = std::max(S.diagonal().cwiseAbs().maxCoeff(), 1e-300);
      const double merit = r.squaredNorm();
      bool stepped = false;
      for (int attempt = 0; attempt < 40 && !stepped; ++attempt) {
        SparseMatrix A = S;
        if (mu > 0.0) A += (mu * k_scale / mass_scale_) * sys_.mass();
        if (!solver_.factorize(A)) {
          mu = std::max(mu * 10.0, 1e-8);
          continue;
        }
        solver_.solve(-r, dq);
        for (double alpha : step_lengths(q, dq)) {
          trial = q + alpha * dq;
          residual(s, trial, r_trial);
          const double m = r_trial.squaredNorm();
          if (std::isfinite(m) && m < (1.0 - 1e-4 * alpha) * merit) {
            q.swap(trial);
            r.swap(r_trial);
            stepped = true;
            break;
          }
        }
        if (stepped) {
          mu *= 0.1;
          if (mu < 1e-12) mu = 0.0;
        } else {
          mu = std::max(mu * 10.0, 1e-8);
        }
      }
      if (!stepped) return out;
    }
  }

 private:
  /// Line-search candidates along dq: the full step; the step cut just past the first switch
  /// that changes sign (a contact closing or opening: beyond it the law changes, so the
  /// linearisation of the full step does not hold); then halvings of the full step.
  std::vector<double> step_lengths(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) {
    std::vector<double> alphas{1.0};
    if (sys_.num_events() > 0) {
      sys_.event_functions(t0_, q, zero_, g0_);
      sys_.event_functions(t0_, q + dq, zero_, g1_);
      double first = 1.0;
      for (Eigen::Index k = 0; k < g0_.size(); ++k)
        if ((g0_[k] > 0.0) != (g1_[k] > 0.0) && g0_[k] != g1_[k])
          first = std::min(first, g0_[k] / (g0_[k] - g1_[k]));
      // 5 % past the crossing: a contact just closed carries stiffness.
      const double cut = std::min(1.0, 1.05 * first);
      if (cut < 0.99) alphas.push_back(std::max(cut, 1e-6));
    }
    for (double a = 0.5; a > 0.01; a *= 0.25) alphas.push_back(a);
    return alphas;
  }

  DrivetrainSystem& sys_;
  double t0_;
  Eigen::VectorXd v0_, zero_, r0_, g0_, g1_;
  double mass_scale_ = 1.0;
  transient::TangentSolver solver_;
};

/// The last increment that failed: its load factor, last iterate and residual there.
struct Failed {
  double s = 0.0;
  Eigen::VectorXd q, r;
};

/// What acts at equation e: loads and held spins, and the elements by their force there
/// (largest first, at most three).
std::string acting_at(const DrivetrainSystem& system, int e, double t0, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& v0) {
  const DrivetrainParts& p = system.parts();
  std::vector<std::string> what;
  for (const LoadTorque& l : p.loads)
    if (l.equation == e) what.push_back("load '" + l.name + "'");
  for (const SpeedDriver& d : p.speed_drivers)
    if (d.equation == e) what.push_back("driver '" + d.name + "' (held)");
  for (const Motor& m : p.motors)
    if (m.equation == e) what.push_back("motor '" + m.name + "' (held)");
  std::vector<std::pair<double, std::string>> forces;
  for (std::size_t k = 0; k < p.elements.size(); ++k) {
    const PlacedElement& pe = p.elements[k];
    const auto it = std::find(pe.equations.begin(), pe.equations.end(), e);
    if (it == pe.equations.end()) continue;
    const Eigen::VectorXd f = system.element_force(k, t0, q, v0);
    const double at = pe.B.col(it - pe.equations.begin()).dot(f);
    forces.emplace_back(std::abs(at), fmt::format("{} ({:.4g})", pe.element->describe(), at));
  }
  std::sort(forces.begin(), forces.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t k = 0; k < forces.size() && k < 3; ++k) what.push_back(forces[k].second);
  if (what.empty()) return "no element, load or driver acts there";
  std::string out = "acting there: ";
  for (std::size_t k = 0; k < what.size(); ++k) out += (k ? ", " : "") + what[k];
  return out;
}

std::string failure_message(const DrivetrainSystem& system, StaticResult& out, const Failed& failed,
                            double t0, const Eigen::VectorXd& v0, const StaticOptions& options) {
  int e = -1;
  if (failed.r.allFinite()) failed.r.cwiseAbs().maxCoeff(&e);
  out.worst_equation = e;
  const std::string where =
      e >= 0 && static_cast<std::size_t>(e) < options.equation_names.size()
          ? fmt::format("equation {} ({})", e, options.equation_names[static_cast<std::size_t>(e)])
          : fmt::format("equation {}", e);
  return fmt::format(
      "static equilibrium not reached: load factor {:.6g} of the loads, preloads and drive "
      "torques reached after {} Newton iterations in {} increments (increments failed down to "
      "{:.3g}); at the full load |r|_inf = {:.3g} (tolerance {:.3g} N); the last failed attempt, "
      "at load factor {:.6g}, left |r| = {:.4g} N or N m at {}, {}; {}. A body held by nothing but "
      "open contacts or inactive bolts has no static "
      "position: give it a support ([[rolling_bearings]], [[bearings]], [[constraints]]), close "
      "the gap (contacts[].gap, contacts[].backlash, gear_meshes[].contact.backlash), activate the "
      "bolt at the start (bolts[].activation_time = 0), hold the spin with a driver ([[drivers]]) "
      "or lower the load (loads[].torque); or start the run without it (static_start = false)",
      out.load_factor, out.iterations, out.increments, options.min_increment, out.residual,
      options.tolerance * out.load_scale, failed.s, e >= 0 ? failed.r[e] : 0.0, where,
      e >= 0 ? acting_at(system, e, t0, failed.q, v0) : std::string("-"),
      system.describe_state(t0, failed.q, v0));
}

}  // namespace

StaticResult solve_static(DrivetrainSystem& system, double t0, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v0, const StaticOptions& options) {
  StaticResult out;
  out.q = q;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());
  Eigen::VectorXd r;
  Failed failed;
  {
    StaticMode mode(system, t0);
    // Load scale: the external and preload forces at the start (never below 1 N).
    Eigen::VectorXd free;
    system.free_residual(t0, out.q, v0, zero, free);
    out.load_scale = std::max(1.0, free.cwiseAbs().maxCoeff());
    const double tol = options.tolerance * out.load_scale;
    LoadPath path(system, t0, out.q, v0);
    double ds = 1.0;
    Eigen::VectorXd trial;
    while (out.load_factor < 1.0 && out.iterations < options.max_iterations) {
      const double s = std::min(1.0, out.load_factor + ds);
      trial = out.q;
      // Intermediate equilibria need not be tight: they only start the next increment.
      const double level_tol = s < 1.0 ? std::max(tol, 1e-6 * out.load_scale) : tol;
      const int budget =
          std::min(options.increment_iterations, options.max_iterations - out.iterations);
      const LoadPath::Outcome o = path.solve(s, trial, level_tol, budget);
      out.iterations += std::max(o.iterations, 1);
      if (o.converged) {
        out.q = trial;
        out.load_factor = s;
        ++out.increments;
        if (o.iterations <= 6) ds = std::min(1.0, 2.0 * ds);
      } else {
        failed = {s, trial, o.r};
        ds *= 0.5;
        if (ds < options.min_increment) break;
      }
    }
    path.residual(1.0, out.q, r);
    out.residual = r.cwiseAbs().maxCoeff();
    system.free_residual(t0, out.q, v0, zero, free);
    for (int e : system.held_equations()) out.held_torques.push_back(free[e]);
  }
  if (!std::isfinite(out.residual)) {
    out.status = Status::Diverged;
    out.message = fmt::format(
        "static equilibrium: the residual is not finite after {} iterations (load factor "
        "{:.6g}); {}",
        out.iterations, out.load_factor, system.describe_state(t0, out.q, v0));
  } else if (out.load_factor < 1.0 || out.residual > options.tolerance * out.load_scale) {
    out.status = Status::NotConverged;
    if (failed.r.size() == 0) failed = {1.0, out.q, r};
    out.message = failure_message(system, out, failed, t0, v0, options);
  }
  return out;
}

std::vector<std::string> equation_names(const fe::DofMap& dofs) {
  static const char* const kComponent[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  std::vector<std::string> names(static_cast<std::size_t>(dofs.num_dofs()));
  for (int e = 0; e < dofs.num_dofs(); ++e) {
    if (!dofs.is_generalized(e)) {
      names[static_cast<std::size_t>(e)] =
          fmt::format("node '{}' {}", dofs.node(dofs.dof_node(e)).name,
                      kComponent[static_cast<int>(dofs.dof_component(e))]);
      continue;
    }
    for (const fe::GeneralizedRange& g : dofs.generalized())
      if (e >= g.first && e < g.first + g.count)
        names[static_cast<std::size_t>(e)] =
            fmt::format("coordinate {} of '{}'", e - g.first, g.name);
  }
  return names;
}

std::string coordinate_unit(const PlacedElement& element, Eigen::Index row,
                            const fe::DofMap& dofs) {
  bool any = false;
  for (std::size_t j = 0; j < element.equations.size(); ++j) {
    if (element.B(row, static_cast<Eigen::Index>(j)) == 0.0) continue;
    const int e = element.equations[j];
    if (e >= dofs.num_dofs() || dofs.is_generalized(e)) return "N";
    if (static_cast<int>(dofs.dof_component(e)) < 3) return "N";
    any = true;
  }
  return any ? "N m" : "N";
}

std::vector<StaticRow> static_table(const DrivetrainSystem& system, const fe::DofMap& dofs,
                                    double t0, const Eigen::VectorXd& v0,
                                    const StaticResult& result,
                                    const std::vector<std::string>& held_names) {
  std::vector<StaticRow> rows;
  const DrivetrainParts& p = system.parts();
  for (std::size_t k = 0; k < p.elements.size(); ++k) {
    const PlacedElement& e = p.elements[k];
    const Eigen::VectorXd f = system.element_force(k, t0, result.q, v0);
    for (Eigen::Index i = 0; i < f.size(); ++i)
      rows.push_back({e.kind + " '" + e.name + "'", fmt::format("force on coordinate {}", i),
                      coordinate_unit(e, i, dofs), f[i]});
  }
  for (std::size_t k = 0; k < result.held_torques.size(); ++k)
    rows.push_back({k < held_names.size() ? held_names[k] : fmt::format("held equation {}", k),
                    "holding torque", "N m", result.held_torques[k]});
  return rows;
}

}  // namespace geardyn::drivetrain
