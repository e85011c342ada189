#pragma once
// Harmonic balance of  M q'' + C q' + K q + f_nl(q) = f_ext(t)  for periodic steady states
// (docs/theory.md §8), with pseudo-arc-length continuation in the excitation frequency.
//
// Unknowns: the Fourier coefficients of every DOF, DOF-major: X[d (2H+1) + c] is coefficient c
// (HarmonicBasis layout [a_0, a_1, b_1, ...]) of DOF d. Residual
//   R(X, omega) = D(omega) X + F_nl(X) - F_ext,
// where D(omega) is block diagonal per harmonic n: for the (a_n, b_n) pair of each DOF pair
//   [ K - (n omega)^2 M    n omega C          ]
//   [ -n omega C           K - (n omega)^2 M  ]
// (cos and sin rows), K for n = 0. F_nl and its Jacobian come from a NonlinearForce evaluated by
// the alternating frequency-time method (harmonic_basis.hpp).
//
// Continuation: Keller's pseudo-arc-length method on y = (X, omega): Euler predictor along the
// unit tangent of R(y) = 0 -- or, for condensed systems (whose tangent costs an iterative solve),
// once two points exist, along the secant of the last two while it turns less than about 6 degrees
// from the direction that led to it (no tangent solve; the tangent again where the curve bends, and
// after a refused step) --, Newton corrector on R(y) = 0 plus t . (y - y_predicted) = 0, step
// length adapted to the corrector's iteration count; a corrected point farther from its predictor
// than the step (it jumped to another part of the curve) is refused and the step halved. It
// passes turning points (folds) of the
// response curve. Where the corrector fails at the smallest step, the point at a small distance
// r (10 min_step, 100 min_step, ... up to 1e-2) on the sphere about the last point is sought
// instead (Crisfield's spherical constraint), away from the segment just traced: a non-smooth fold
// (a contact that grazes) turns the curve back by more than 90 degrees, which the plane misses.
// A point that neither finds is reported (frequency, iterations, residual), never dropped: the
// curve ends there with Status::NotConverged.
// Reference: Seydel, "Practical Bifurcation and Stability Analysis", 3rd ed., Springer (2010),
// ch. 4; Crisfield, "A fast incremental/iterative solution procedure that handles snap-through",
// Computers & Structures 13 (1981) 55-62; Krack & Gross, "Harmonic Balance for Nonlinear Vibration
// Problems", Springer (2019).
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"
#include "geardyn/hbm/jenkins.hpp"

namespace geardyn::hbm {

/// F_nl(X) and dF_nl/dX for the coefficient vector X (size n_dof (2H+1)); F and J are sized by
/// the caller and zero on entry; the force adds its contribution.
using NonlinearForce = std::function<void(const HarmonicBasis& basis, const Eigen::VectorXd& X,
                                          Eigen::VectorXd& F, Eigen::MatrixXd& J)>;

/// f = alpha q_dof^3 (a hardening spring for alpha > 0), exact in the AFT when
/// time_samples > 4H.
NonlinearForce cubic_spring(int dof, double alpha);

/// A Jenkins friction element (jenkins.hpp) between DOF a and DOF b (b = -1: ground) acting on
/// the relative displacement u = q_a - q_b: the force T on a, -T on b. Its Jacobian is the
/// analytic one of jenkins_response.
NonlinearForce jenkins_force(int dof_a, int dof_b, JenkinsElement element);

/// A harmonic-balance problem R(X, omega) = 0 in the unknowns X (Fourier coefficients in the
/// HarmonicBasis layout, DOF-major): what continue_in_frequency traces. HarmonicBalance below is
/// the form with physical M, C, K; CondensedHarmonicBalance (condensed.hpp) the form with the
/// linear receptance at the nonlinear coordinates.
class HarmonicSystem {
 public:
  virtual ~HarmonicSystem() = default;
  /// Number of unknowns.
  virtual int size() const = 0;
  /// R(X, omega); with J non-null also dR/dX, with dR_domega non-null also dR/domega.
  virtual Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega,
                                   Eigen::MatrixXd* J = nullptr,
                                   Eigen::VectorXd* dR_domega = nullptr) const = 0;
  /// The magnitude against which ||R|| is judged converged (a force for the physical form, a
  /// displacement for the receptance form), at (X, omega); > 0.
  virtual double residual_scale(const Eigen::VectorXd& X, double omega) const = 0;
};

class HarmonicBalance final : public HarmonicSystem {
 public:
  /// M, C, K square of one size n_dof; F_ext of size n_dof (2H+1) in the unknowns' layout.
  /// Throws InputError on mismatched sizes.
  HarmonicBalance(Eigen::MatrixXd M, Eigen::MatrixXd C, Eigen::MatrixXd K, HarmonicBasis basis,
                  std::vector<NonlinearForce> forces, Eigen::VectorXd F_ext);

  int dofs() const { return static_cast<int>(K_.rows()); }
  /// Number of unknowns n_dof (2H+1).
  int size() const override { return dofs() * basis_.size(); }
  const HarmonicBasis& basis() const { return basis_; }
  const Eigen::VectorXd& external_force() const { return F_ext_; }

  /// R(X, omega); with J non-null also dR/dX, with dR_domega non-null also dR/domega.
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double omega, Eigen::MatrixXd* J = nullptr,
                           Eigen::VectorXd* dR_domega = nullptr) const override;
  /// max(1, ||F_ext||): forces in the model's units.
  double residual_scale(const Eigen::VectorXd& X, double omega) const override;
  const Eigen::MatrixXd& mass() const { return M_; }
  const Eigen::MatrixXd& damping() const { return C_; }
  const Eigen::MatrixXd& stiffness() const { return K_; }

  /// Amplitude sqrt(a_n^2 + b_n^2) of harmonic n >= 1 of DOF d in X.
  double amplitude(const Eigen::VectorXd& X, int dof, int harmonic) const;

 private:
  Eigen::MatrixXd M_, C_, K_;
  HarmonicBasis basis_;
  std::vector<NonlinearForce> forces_;
  Eigen::VectorXd F_ext_;
};

struct ContinuationOptions {
  double omega_start = 0.0;  ///< [rad/s] (any consistent unit)
  double omega_end = 0.0;
  /// The arc length is measured in y = (X / x_scale, omega / omega_scale): choose the scales so
  /// that a typical response amplitude and the frequency range are both of order one, or the
  /// steps follow one of them only and turning points are cut.
  double x_scale = 1.0;
  double omega_scale = 1.0;
  double step = 0.01;  ///< first arc-length step (in the scaled (X, omega) norm)
  double min_step = 1e-7;
  double max_step = 0.1;
  int max_points = 20000;
  double tolerance = 1e-10;  ///< ||R|| <= tolerance * HarmonicSystem::residual_scale
  int max_iterations = 20;   ///< Newton iterations per point
};

struct ContinuationPoint {
  double omega = 0.0;
  Eigen::VectorXd X;
  int iterations = 0;
  double residual = 0.0;  ///< ||R|| at the converged point
  /// Sign of the branch-point test function det [dR/dy; t^T] at the point (t the unit tangent
  /// along the direction of travel; Seydel 2010, sec. 5.3): regular along a branch and through
  /// its turning points, it changes sign at a simple branch point (a bifurcation of the same
  /// period). 0: not known (the first point, a point found on a sphere, a condensed system
  /// solved iteratively).
  int test_sign = 0;
};

struct ContinuationResult {
  Status status = Status::Ok;
  std::string message;  ///< empty when ok; otherwise where and why the curve ended
  std::vector<ContinuationPoint> points;
  /// Indices i of points where test_sign differs from the last known sign before i: a simple
  /// branch point lies between point i and the one before it with a known sign.
  std::vector<int> branch_points;
};

/// The branch points of a traced curve (see ContinuationResult::branch_points).
std::vector<int> branch_points(const std::vector<ContinuationPoint>& points);

/// Traces the periodic solutions from omega_start to omega_end, starting from the guess X0 at
/// omega_start (corrected by Newton first).
ContinuationResult continue_in_frequency(const HarmonicSystem& hb, const Eigen::VectorXd& X0,
                                         const ContinuationOptions& options);

}  // namespace geardyn::hbm
