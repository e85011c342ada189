#pragma once
// The one interface of geardyn's nonlinear force elements (gear tooth contact, end stops and
// rattle contacts, rolling-element bearings, bushings, bolted joints): a force and its tangents
// from the relative displacement and velocity of the element's two ends, so that the same element
// serves the time-domain solver, harmonic balance (alternating frequency-time) and the
// linearisation at an operating point (docs/theory.md §16).
//
// Conventions (stated once here):
//   * An element has n relative coordinates in its own frame (a contact along a direction: 1; a
//     bushing: 6, three translations then three small rotations). u = (end j) - (end i) in those
//     coordinates, v = du/dt; an element to ground has end i fixed.
//   * `force` is the element's internal (restoring) force on its coordinates: the solver adds
//     +force to the residual of end j and -force to end i (M a + ... + f_int(u, v, t) = f_ext).
//     A linear spring has force = k u and stiffness = +k.
//   * stiffness = d force / d u and damping = d force / d v, the analytic tangents (n x n) that
//     the implicit solver's Newton iteration and the linearisation use; every element's tests
//     check them against central differences.
//   * t is the time [s] for elements with a schedule (a bolt's activation); elements without one
//     ignore it.
//   * evaluate() is const and keeps no scratch state: one element may be evaluated from several
//     threads at once. History-dependent elements (friction with stick and slip) will add an
//     explicit state that the solver commits after a converged step; none is needed so far.
#include <Eigen/Core>
#include <string>

namespace geardyn::elements {

/// Force and tangents of one element at one state.
struct ElementForce {
  Eigen::VectorXd force;      ///< internal force on the n relative coordinates [N, N m]
  Eigen::MatrixXd stiffness;  ///< d force / d u (n x n)
  Eigen::MatrixXd damping;    ///< d force / d v (n x n)

  /// Sized n and zeroed.
  void reset(Eigen::Index n) {
    force.setZero(n);
    stiffness.setZero(n, n);
    damping.setZero(n, n);
  }
};

class ForceElement {
 public:
  virtual ~ForceElement() = default;
  /// Number n of relative coordinates.
  virtual Eigen::Index size() const = 0;
  /// Force and tangents at relative displacement `u` and velocity `v` (size n) at time `t`.
  virtual void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                        ElementForce& out) const = 0;
  /// What the element is, for messages and tables: e.g. "bolt 'B3'", "contact 'stop'".
  virtual std::string describe() const = 0;

  /// Number of switching functions: g_k(u, t) whose sign changes mark the kinks of the law (a
  /// contact closing or opening, a bolted joint separating). An adaptive integrator locates
  /// them in time. Default: none (a smooth element).
  virtual int num_switches() const { return 0; }
  /// g_k(u, t) for k < num_switches(), written to g[0 .. num_switches() - 1].
  virtual void switches(const Eigen::VectorXd& /*u*/, double /*t*/, double* /*g*/) const {}
  /// What switch k is, short, without the element: e.g. "upper side" (event reports prefix the
  /// element).
  virtual std::string describe_switch(int k) const { return "switch " + std::to_string(k); }
};

/// Largest deviation of an element's analytic tangents from central differences of its force,
/// relative to the largest tangent entry (and at least `floor` in absolute terms).
struct TangentCheck {
  double stiffness_error = 0.0;  ///< max |K - K_fd| / max(max |K_fd|, floor)
  double damping_error = 0.0;    ///< max |C - C_fd| / max(max |C_fd|, floor)
};

/// Central differences of `element` at (u, v, t) with steps h_u (displacements) and h_v
/// (velocities). A kink of the law within a step (a contact closing) makes the differences
/// meaningless there: check away from kinks.
TangentCheck check_tangents(const ForceElement& element, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v, double t, double h_u, double h_v,
                            double floor = 1e-12);

}  // namespace geardyn::elements
