#pragma once
// The one interface of a nonlinear force element in harmonic balance and in the periodic time
// analyses that check it (monodromy stability, time-marched steady states): docs/theory.md §8.
//
// An element acts on n local coordinates u (relative displacements or rotations in its own
// frame, u = B q for the system's DOFs q, see element_system.hpp). Its internal (restoring)
// force f enters the equations of motion as
//   M q'' + C q' + K q + sum_e B_e^T f_e(u_e, u_e', theta; state_e) = f_ext(theta),
// theta = omega t the phase of the periodic solution (omega: the fundamental, the excitation
// frequency). A time-varying law (a gear mesh's stiffness over the mesh cycle) depends on theta;
// most laws ignore it. Hysteretic laws (a Jenkins slider, a friction contact) carry an internal
// state (the slider's position or the tangential force) that the time march commits step by
// step.
//
// Two ways to evaluate an element:
//   * harmonic_force: the alternating frequency-time (AFT) evaluation of harmonic balance. The
//     element receives the Fourier coefficients w of its coordinates, coordinate-major
//     (w[j (2H+1) + c], c in the HarmonicBasis layout [a_0, a_1, b_1, ...]), and writes the
//     coefficients f of its force (same layout), with its exact Jacobian J = df/dw and, when the
//     law depends on omega or theta, df/domega. Hysteretic laws march their state over the
//     period until it repeats (the steady loop).
//   * time_force: the law at one time step, for time integration: the force at (u, v, theta)
//     reached from the committed `state` of the step's start, with the tangents, and the state
//     to commit when the step is accepted.
#include <Eigen/Dense>
#include <limits>
#include <string>

#include "geardyn/hbm/harmonic_basis.hpp"

namespace geardyn::hbm {

/// The force of an element at one time step (time_force).
struct ElementStep {
  Eigen::VectorXd force;      ///< f (n) [N, N m]
  Eigen::MatrixXd stiffness;  ///< df/du (n x n), for the step's state
  Eigen::MatrixXd damping;    ///< df/dv (n x n)
  Eigen::VectorXd state;      ///< the state to commit when the step is accepted (state_size())
};

/// What an AFT evaluation of an element reports besides its force, for tables.
struct ElementLoop {
  double energy_per_cycle = 0.0;  ///< closed-loop integral of f . du over one period [J]
  /// Share of the period in each regime, where the law has them (stick / slip / open); NaN
  /// where it does not.
  double stick_fraction = std::numeric_limits<double>::quiet_NaN();
  double slip_fraction = std::numeric_limits<double>::quiet_NaN();
  double open_fraction = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd displacement;  ///< u over the period's samples (n_time x n)
  Eigen::MatrixXd force;         ///< f over the period's samples (n_time x n)
};

class NonlinearElement {
 public:
  virtual ~NonlinearElement() = default;

  /// Number n >= 1 of local coordinates.
  virtual int size() const = 0;
  /// What the element is, for messages and tables: e.g. "jenkins 'root'".
  virtual std::string describe() const = 0;

  /// AFT: the force coefficients f (n (2H+1), sized and zero on entry) for the coordinate
  /// coefficients w at fundamental frequency omega > 0 [rad/s]; with J non-null (sized and zero)
  /// df/dw, with df_domega non-null (sized and zero) df/domega. Throws NumericalError when the
  /// law cannot be evaluated (a non-finite input).
  virtual void harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                              Eigen::VectorXd& f, Eigen::MatrixXd* J,
                              Eigen::VectorXd* df_domega) const = 0;

  /// The AFT derivative of the force coefficients with respect to the Fourier coefficients z of
  /// the coordinates' velocity u' = du/dt (coordinate-major like w): per coordinate pair
  /// P diag(df/dv) Q at the motion w, omega. Jv (n (2H+1) square, sized and zero on entry)
  /// gets it added. Hill's method needs it: a perturbation e^{lambda t} p(t) of the motion adds
  /// e^{lambda t} (lambda p + p') to the velocity, and harmonic_force's J (through
  /// v = omega Q' w) carries the p' part only. Default: nothing (laws without velocity
  /// dependence; the hysteretic laws here are rate-independent).
  virtual void harmonic_velocity_jacobian(const HarmonicBasis& /*basis*/,
                                          const Eigen::VectorXd& /*w*/, double /*omega*/,
                                          Eigen::MatrixXd& /*Jv*/) const {}

  /// The periodic loop of the solution with coordinate coefficients w: samples of u and f over
  /// the steady period, the energy dissipated per cycle and the share of each regime.
  virtual ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                           double omega) const = 0;

  /// Size of the internal state of the time-domain law (0: a law without memory).
  virtual int state_size() const { return 0; }
  /// The state of the element at rest at displacement u (a slider stuck there).
  virtual Eigen::VectorXd initial_state(const Eigen::VectorXd& u) const;
  /// The law at one time step: displacement u, velocity v, phase theta = omega t [rad] and
  /// fundamental omega [rad/s] (for time-varying laws: their rate is d/dt = omega d/dtheta),
  /// from the committed state of the step's start.
  virtual void time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta,
                          double omega, const Eigen::VectorXd& state, ElementStep& out) const = 0;
};

/// An element without memory: f(u, v, theta) at every instant. harmonic_force and loop come
/// from the pointwise law by the AFT:
///   f_c = P f(Q w, omega Q' w, theta_j),  J = P diag(df/du) Q + omega P diag(df/dv) Q',
///   df/domega = P diag(df/dv) Q' w   (velocity-dependent laws)
///               + P (df/domega at fixed u, v)   (pointwise_omega_derivative),
/// with Q the sampling matrix, Q' its theta derivative and P the projection (harmonic_basis.hpp);
/// exact for the samples taken.
class PointwiseElement : public NonlinearElement {
 public:
  /// f, df/du, df/dv at one instant (out sized n, n x n, n x n and zero on entry) at phase
  /// theta and fundamental omega.
  virtual void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta,
                         double omega, ElementStep& out) const = 0;
  /// True when the law depends on the velocity (then df/domega is not zero).
  virtual bool velocity_dependent() const { return false; }
  /// A law that depends on omega other than through v (a time-varying law whose rate
  /// omega d/dtheta enters, e.g. a mesh's unloaded TE rate) overrides this: df/domega at fixed
  /// u and v (out: n, zero on entry). Default: no such dependence.
  virtual void pointwise_omega_derivative(const Eigen::VectorXd& /*u*/,
                                          const Eigen::VectorXd& /*v*/, double /*theta*/,
                                          double /*omega*/, Eigen::VectorXd& /*out*/) const {}

  void harmonic_force(const HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                      Eigen::VectorXd& f, Eigen::MatrixXd* J,
                      Eigen::VectorXd* df_domega) const override;
  /// P diag(df/dv) Q per coordinate pair from the pointwise law (nothing when not
  /// velocity_dependent()).
  void harmonic_velocity_jacobian(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                  double omega, Eigen::MatrixXd& Jv) const override;
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                   double omega) const override;
  void time_force(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                  const Eigen::VectorXd& state, ElementStep& out) const override;
};

/// Samples u_j (n_time x n) and, with omega, v_j = omega du/dtheta of coordinate coefficients
/// w (coordinate-major).
Eigen::MatrixXd sample_coordinates(const HarmonicBasis& basis, const Eigen::VectorXd& w);
Eigen::MatrixXd sample_velocities(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                  double omega);

/// The theta-derivative matrix Q' of the sampling matrix: d/dtheta of x(theta_j) = Q'_j c.
Eigen::MatrixXd sampling_derivative(const HarmonicBasis& basis);

/// P diag(c) Q (size() x size()) for the samples c (time_samples()): the AFT Jacobian
/// d(P f(Q w))/dw of a pointwise law with slope c_j = df/du at sample j. Formed from the sums
/// C_k + i S_k = (1/n) sum_j c_j e^{i k theta_j}, k = 0 .. 2H (one real FFT of c), by
/// 2 cos a cos b = cos(a - b) + cos(a + b) and the like: entry (cos h, cos g) is
/// C_{h-g} + C_{h+g}, (cos h, sin g) S_{h+g} - S_{h-g}, (sin h, cos g) S_{h+g} + S_{h-g},
/// (sin h, sin g) C_{h-g} - C_{h+g}; row a_0: C_g, S_g; column a_0: 2 C_h, 2 S_h. Equal to the
/// product of the matrices to round-off, in O(n log n + H^2) instead of O(n H^2).
Eigen::MatrixXd projected_diagonal(const HarmonicBasis& basis,
                                   const Eigen::Ref<const Eigen::VectorXd>& c);
/// P diag(c) Q' (Q' = sampling_derivative(basis)): the columns of projected_diagonal mixed as
/// those of Q' are.
Eigen::MatrixXd projected_diagonal_derivative(const HarmonicBasis& basis,
                                              const Eigen::Ref<const Eigen::VectorXd>& c);

/// Closed-loop integral sum_j f_{j+1/2} . (u_{j+1} - u_j) over periodic samples (trapezoidal
/// rule), rows = samples.
double loop_energy(const Eigen::MatrixXd& u, const Eigen::MatrixXd& f);

}  // namespace geardyn::hbm
