#pragma once
// Periodic time analyses of an ElementSystem (element_system.hpp) at the fundamental omega, the
// time-domain checks of harmonic balance (issue #18, items 4 and 5; docs/theory.md §8):
//   * PeriodicIntegrator: integration of
//       M q'' + C q' + K q + sum_e B_e^T f_e(B_e q, B_e q', theta; s_e) = lambda f_ext(theta),
//     theta = omega t, over whole periods T = 2 pi / omega with a fixed number N of steps per
//     period (theta_k = 2 pi k / N exactly), state z = (q, q', element states s_e);
//   * march_to_periodic: the steady state of that march (periods until z at theta = 0 repeats);
//   * monodromy: the Floquet multipliers of a harmonic-balance solution from the monodromy matrix
//     Phi = dz(T)/dz(0) of the flow over one period, through the actual (e.g. stick-slip) law.
//
// Schemes (TimeScheme):
//   * Newmark average acceleration (the default: gamma = 1/2, beta = 1/4), Newton on
//       [ (4/h^2) M + (2/h) C + K + sum_e B_e^T (K_e + (2/h) C_e) B_e ] dq = -r
//     with the elements' tangents K_e = df/du, C_e = df/dv (time_force), each element's force
//     evaluated from its state committed at the step's start and its new state committed when
//     the step converges (the return mapping of a slider). Chosen as the default because it is
//     unconditionally stable for linear(ised) systems, so a stiff contact (k_contact >> k) does
//     not limit the step, it adds no numerical damping (the energy of a linear undamped system is
//     kept, a Floquet multiplier on the unit circle stays on it) and is second order. Its one
//     error is a frequency warping: a linear mode w is integrated at (2/h) arctan(w h / 2), a
//     relative shift -(w h)^2 / 12, 7.8e-7 at N = 2048 for w = omega (Hughes, "The Finite
//     Element Method", Dover (2000), §9.3); near a resonance of quality factor Q the response
//     amplitude errs by up to ~Q times that.
//   * classical Runge-Kutta 4 on the first-order form (q, q')' = (q', M^-1 (...)), the element
//     state of the step's start held over the four stages and the new one committed at the end.
//     Fourth order for smooth laws (1e-9 on a Duffing steady state where Newmark gives 5e-6),
//     explicit: stable only for omega_max h < 2.8, i.e. N > 2.2 omega_max / omega for the highest
//     natural frequency omega_max of the linearised system; for soft smooth problems only (a
//     Duffing oscillator, a Mathieu equation), never for stiff contacts. Across a stick-slip
//     switch both schemes are first order (the switch falls inside a step).
// M must be invertible (the acceleration at the start of each period comes from the equation of
// motion): condense massless DOFs first. K_loss (hysteretic loss on harmonics n >= 1) has no
// time-domain form: a system with it is rejected (InputError).
//
// Monodromy by central finite differences of the flow map: column j of Phi is
//   (z(T; z0 + d_j e_j) - z(T; z0 - d_j e_j)) / (2 d_j),  d_j = fd_step * scale_j,
// scale_j the largest |z_j| over the period of the solution (its DOF's, velocity's or state's
// amplitude; when zero, the largest among the q's, and 1 for a zero solution: a linear problem,
// where any step gives the same columns). Chosen over the variational equations because
// NonlinearElement::time_force returns df/du and df/dv but not the derivatives with respect to
// the element's state (nor the new state's derivatives), which a slider's variational equation
// needs; the difference quotient goes through the same time_force as the march, for any element.
// Its errors: truncation O(d^2) (zero for a linear law; 1e-10 relative for fd_step = 1e-5 on a
// cubic law), the Newton noise (relative increment 1e-13) divided by fd_step (1e-8), and the
// scheme's own error (above). Through stick-slip the flow map is piecewise smooth (the step of a
// switch changes with z0); a difference quotient straddling such a kink averages two one-sided
// derivatives that differ by O(h). Cost: 2 (2 n_dof + n_states) + 1 integrations of one period.
// Phi is formed in the scaled coordinates z_j / scale_j (same eigenvalues, entries of order 1).
//
// Start of the monodromy: q(0) = sum a_n, q'(0) = omega sum n b_n from the HB coefficients X; the
// element states come from marching each element's law along the HB motion u = B q(theta) over
// `preliminary_periods` periods from initial_state(u(0)), so that a slider starts on its steady
// loop. (A slider that never slips keeps initial_state(u(0)), whereas the HB Jenkins sticks about
// the mean position a_0: the force offset differs by a constant and the trajectory is then not
// exactly periodic; `closure_error` reports how far z(T) is from z(0).)
//
// Neutral element states. A slider stuck over the whole period keeps its state (w(T) = w(0)
// exactly and independently of small perturbations of q, q', as long as its time_force returns
// the state unchanged in stick, as a return mapping does), so its row of Phi is the unit row
// e_j^T and Phi has the multiplier 1 exactly: the family of periodic solutions of a stuck slider
// at every position (a continuum, neutral). It is not a fold. Such states are detected (row of
// the scaled Phi within neutral_tolerance of e_j^T), counted in `neutral_states` and excluded:
// the multipliers are the eigenvalues of Phi without their rows and columns, which are exactly
// the remaining eigenvalues since Phi is block triangular in that ordering. A slider that slips
// forgets its initial state: its multipliers are near 0 (exponent -> -inf; exactly 0 gives
// exponent -infinity, reported as such).
//
// Kinds, as in stability.hpp, from the multiplier rho of largest modulus when it exceeds
// 1 + stability_tolerance: exponent lambda = log(rho) / T (principal branch, Im in
// (-omega/2, omega/2]); instability_kind(lambda, omega, kind_tolerance): Fold (real rho > 1),
// PeriodDoubling (real rho < -1), NeimarkSacker (complex pair).
//
// Against Hill's method (stability.hpp): on smooth laws both give the same multipliers (Duffing:
// within 5e-7 with RK4, the HB truncation at H = 7). On a Jenkins-damped oscillator Hill's method
// on the AFT Jacobian reports max Re lambda = -c / 2m at every point: that Jacobian is a periodic
// stiffness (k_t in stick, 0 in slip), so the friction's damping of perturbations is missing,
// which the monodromy sees (|rho| = 0.43 against exp(-c T / 2m) = 0.96; monodromy_test.cpp).
// References: Seydel, "Practical Bifurcation and Stability Analysis", 3rd ed., Springer (2010),
// ch. 7 (monodromy, multipliers, their crossings); Nayfeh & Balachandran, "Applied Nonlinear
// Dynamics", Wiley (1995), ch. 3.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::hbm {

enum class TimeScheme {
  Newmark,     ///< average acceleration, Newton on the element tangents (default; stiff laws)
  RungeKutta4  ///< classical explicit RK4 (smooth, non-stiff laws; accurate)
};

struct TimeMarchOptions {
  int steps_per_period = 2048;  ///< N >= 16
  TimeScheme scheme = TimeScheme::Newmark;
  double load_factor = 1.0;  ///< lambda on f_ext
  /// Newton (Newmark): converged when max |dq| <= newton_tolerance * max(|q|, h |q'|, h^2 |q''|).
  double newton_tolerance = 1e-13;
  int max_newton_iterations = 30;
  /// march_to_periodic: converged when z at the start of consecutive periods differs by at most
  /// closure_tolerance times the amplitude (max |q| over the period; q' / omega with q).
  double closure_tolerance = 1e-10;
  int max_periods = 2000;  ///< march_to_periodic gives up (NotConverged) after these

  /// Throws InputError naming every out-of-range field.
  void validate() const;
};

/// The state z of the march at a phase: q, q' [per s] and each element's state.
struct TimeState {
  Eigen::VectorXd q, v;
  std::vector<Eigen::VectorXd> element_states;  ///< one per placed element (state_size())
};

/// Integrator of an ElementSystem over whole periods at fundamental omega. Keeps a copy of the
/// system (elements shared); const and thread-safe.
class PeriodicIntegrator {
 public:
  /// Throws InputError on an invalid system (ElementSystem::validate), K_loss non-empty,
  /// omega <= 0, a singular M or invalid options.
  PeriodicIntegrator(ElementSystem system, double omega, TimeMarchOptions options = {});

  /// Samples of one period: row k = the value at theta_k = 2 pi k / N, k = 0 .. N.
  struct Record {
    Eigen::MatrixXd q, v;  ///< (N + 1) x n_dof
  };

  /// Advances z from theta = 0 over one period (to theta = 2 pi, i.e. back to phase 0); with
  /// `record`, the samples. Returns Status::Ok, or Status::Diverged (non-finite state, Newton
  /// not converged) with `message` saying at which step.
  Status advance_period(TimeState& z, Record* record, std::string& message) const;

  /// The state at rest-compatible start: q, v and each element's initial_state(B q).
  TimeState start_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  const ElementSystem& system() const { return system_; }
  double omega() const { return omega_; }
  const TimeMarchOptions& options() const { return options_; }
  /// Total number of element state entries (the z's third part).
  int state_count() const;

 private:
  struct Workspace;
  void element_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double theta,
                      const std::vector<Eigen::VectorXd>& states, Workspace& w,
                      bool tangents) const;
  Eigen::VectorXd acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double theta,
                               const std::vector<Eigen::VectorXd>& states, Workspace& w) const;
  bool newmark_step(TimeState& z, Eigen::VectorXd& a, int k, Workspace& w) const;
  bool rk4_step(TimeState& z, int k, Workspace& w) const;

  ElementSystem system_;
  double omega_;
  TimeMarchOptions options_;
  double h_;  ///< time step T / N [s]
  Eigen::PartialPivLU<Eigen::MatrixXd> mass_lu_;
};

/// The steady periodic state reached by a time march (march_to_periodic).
struct PeriodicMarchResult {
  Status status = Status::Failed;  ///< Ok, NotConverged (not periodic at T), Diverged
  std::string message;             ///< empty when Ok; otherwise what happened
  /// q at the basis' sample phases theta_j = 2 pi j / n_time of the last period (n_time x n_dof;
  /// between steps by cubic Hermite interpolation on q and q').
  Eigen::MatrixXd samples;
  /// Fourier coefficients of the last period, DOF-major in the basis' layout (X[d (2H+1) + c]),
  /// by the rectangle rule over the N steps (exact up to harmonic N/2 - 1).
  Eigen::VectorXd coefficients;
  int periods = 0;             ///< periods integrated
  double closure_error = 0.0;  ///< last max |z_k - z_{k-1}| / amplitude (see closure_tolerance)
  /// Ratio of the last two closure errors: the contraction per period of the transient (the
  /// largest Floquet multiplier's modulus, when it dominates); the distance to the periodic
  /// state is about closure_error * contraction / (1 - contraction).
  double contraction = 0.0;
  TimeState start;  ///< z at the start of the last period
  /// The closure error after each period (closure_history.back() = closure_error): the decay of
  /// the transient, at the rate of the largest Floquet multiplier's modulus.
  std::vector<double> closure_history;
};

/// Marches the system at omega from q(0) = q0, q'(0) = v0 (element states: initial_state(B q0))
/// until z at theta = 0 repeats within options.closure_tolerance, or options.max_periods. A
/// response that is not periodic at T (quasi-periodic, chaotic, a subharmonic, or a transient
/// decaying too slowly) is returned as Status::NotConverged with its closure error, and a
/// period-2 response (z repeats after two periods within 1000 closure_tolerance: after a period
/// doubling) is named as such; never hidden. Throws InputError as PeriodicIntegrator, when q0, v0
/// are not n_dof long and when the basis' H >= N / 2 (its harmonics would alias in the steps).
PeriodicMarchResult march_to_periodic(const ElementSystem& system, double omega,
                                      const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                      const HarmonicBasis& basis,
                                      const TimeMarchOptions& options = {});
/// Same from a full state (element states given).
PeriodicMarchResult march_to_periodic(const ElementSystem& system, double omega, TimeState start,
                                      const HarmonicBasis& basis,
                                      const TimeMarchOptions& options = {});

struct MonodromyOptions {
  TimeMarchOptions march;             ///< scheme, steps per period, Newton (load_factor included)
  double fd_step = 1e-5;              ///< relative step d_j / scale_j of the difference quotients
  int preliminary_periods = 2;        ///< of the element states along the HB motion, >= 1
  double stability_tolerance = 1e-6;  ///< stable when every |rho| <= 1 + this
  double kind_tolerance = 1e-3;       ///< as HillOptions::kind_tolerance, in (0, 0.25)
  double neutral_tolerance = 1e-9;    ///< of a neutral state's unit row in the scaled Phi

  /// Throws InputError naming every out-of-range field.
  void validate() const;
};

struct MonodromyResult {
  /// Multipliers (eigenvalues of Phi, neutral states excluded) by decreasing modulus, exponents
  /// log(rho) / T, max_real_part, stable, kind, status and message; centroids empty and
  /// sorting_gap NaN (Hill's method only).
  FloquetResult floquet;
  /// Phi in the scaled coordinates z_j / scale_j, z = (q, q', element states), before the
  /// exclusion of neutral states.
  Eigen::MatrixXd monodromy;
  Eigen::VectorXd scales;  ///< scale_j
  int neutral_states = 0;  ///< element states excluded (a stuck slider's multiplier 1)
  /// max |z(T) - z(0)| of the unperturbed start, scaled: how periodic the HB solution is in the
  /// time scheme (the scheme's and the truncation's error; large when X is not a solution).
  double closure_error = 0.0;
};

/// The monodromy matrix and Floquet multipliers of the periodic solution with HB coefficients X
/// (DOF-major in `basis`' layout) of `system` at omega (see the header comment). Throws
/// InputError as PeriodicIntegrator and when X has not n_dof (2H+1) entries; a failed
/// integration or eigen-solve is returned in floquet.status (Diverged / Failed) with a message.
MonodromyResult monodromy(const ElementSystem& system, double omega, const Eigen::VectorXd& X,
                          const HarmonicBasis& basis, const MonodromyOptions& options = {});

/// monodromy(...).floquet.
FloquetResult monodromy_stability(const ElementSystem& system, double omega,
                                  const Eigen::VectorXd& X, const HarmonicBasis& basis,
                                  const MonodromyOptions& options = {});

}  // namespace geardyn::hbm
