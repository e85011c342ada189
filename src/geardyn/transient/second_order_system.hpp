#pragma once
// What a time integrator sees of the physics (STYLE.md, "Chrono"): a second-order system
//   r(t, q, v, a) = M a + f_int(q, v, t) - f_ext(t) = 0,       v = q', a = q''
// through its residual and its tangent. A linear rotor (linear_rotor_system.hpp) and, later, a
// nonlinear drivetrain with contacts implement it; the integrators (integrator.hpp) know nothing
// else about them.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>

namespace geardyn::transient {

using SparseMatrix = Eigen::SparseMatrix<double>;

class SecondOrderSystem {
 public:
  virtual ~SecondOrderSystem() = default;

  /// Number of unknowns n.
  virtual int size() const = 0;

  /// r = M a + f_int(q, v, t) - f_ext(t); r is resized to n. Must not keep references.
  virtual void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        const Eigen::VectorXd& a, Eigen::VectorXd& r) = 0;

  /// Tangent S = c_m M + c_c C_t + c_k K_t at (t, q, v), with C_t = d f_int / d v and
  /// K_t = d f_int / d q, as a sparse n x n matrix (any storage order; S is overwritten).
  /// Where the tangent has a dense low-rank part (modal damping), that part is left out here and
  /// returned by tangent_low_rank.
  virtual void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m,
                       double c_c, double c_k, SparseMatrix& S) = 0;

  /// Optional low-rank part of the tangent: S_total = S + U diag(d) U^T with U n x m, m << n
  /// (e.g. modal damping c_c B diag(2 zeta_r omega_r) B^T). Returns false (and leaves U, d
  /// alone) when there is none. The solver applies it with the Woodbury identity, never densely.
  virtual bool tangent_low_rank(double /*t*/, const Eigen::VectorXd& /*q*/,
                                const Eigen::VectorXd& /*v*/, double /*c_m*/, double /*c_c*/,
                                double /*c_k*/, Eigen::MatrixXd& /*U*/, Eigen::VectorXd& /*d*/) {
    return false;
  }

  /// True when M, C_t and K_t are constant (f_int linear in q and v, independent of t): the
  /// integrator then factors the tangent once and takes one Newton correction per step, which
  /// solves the linear step equations exactly.
  virtual bool is_linear_time_invariant() const { return false; }

  /// Called once a step has converged, with the accepted state at its end. A system with history
  /// (friction stick/slip, bolt preload sequence) commits its internal variables here; the
  /// residual calls of the next step see them.
  virtual void commit_step(double /*t*/, const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& /*v*/,
                           const Eigen::VectorXd& /*a*/) {}

  /// Number of event functions: switching functions g_k(t, q, v) whose sign changes mark a
  /// discontinuity of the equations (a contact closing or opening, a clutch locking). An
  /// adaptive integrator locates them in time and restarts its step there.
  virtual int num_events() const { return 0; }
  /// g_k(t, q, v), k < num_events(); g is resized to num_events().
  virtual void event_functions(double /*t*/, const Eigen::VectorXd& /*q*/,
                               const Eigen::VectorXd& /*v*/, Eigen::VectorXd& g) const {
    g.resize(0);
  }
  /// What event function k is, for reports: e.g. "contact 'stop' closes / opens".
  virtual std::string describe_event(int k) const { return "event " + std::to_string(k); }
  /// A diagnosis of the state for a failure message (the element with the largest force or
  /// penetration, ...); empty when the system has none.
  virtual std::string describe_state(double /*t*/, const Eigen::VectorXd& /*q*/,
                                     const Eigen::VectorXd& /*v*/) const {
    return {};
  }
};

}  // namespace geardyn::transient
