#pragma once
// Local stability of a periodic solution found by harmonic balance: Floquet exponents by Hill's
// method, from the harmonic-balance Jacobian alone (no time integration).
//
// System and conventions are those of harmonic_balance.hpp: M q'' + C q' + K q + f_nl(q) =
// f_ext(t), Fourier coefficients DOF-major, X[d (2H+1) + c], c in [a_0, a_1, b_1, ..., a_H, b_H]
// (harmonic_basis.hpp), theta = omega t, residual rows = cos / sin coefficients of the equation.
//
// A perturbation y(t) = e^{lambda t} p(t) of the periodic solution q(t), p T-periodic
// (T = 2 pi / omega) with coefficients P, satisfies the variational equation
//   M y'' + C y' + (K + df_nl/dq(q(t))) y = 0.
// With y' = e^{lambda t} (lambda p + p') and y'' = e^{lambda t} (lambda^2 p + 2 lambda p' + p''),
// balancing the kept harmonics gives the quadratic eigenproblem (Hill's method)
//   (lambda^2 D2 + lambda D1 + J) P = 0,                                                 (1)
// where J = dR/dX at the solution (the Fourier coefficients of M p'' + C p' + K p + f_nl' p),
//   D2 = M on every coefficient (M (x) I_{2H+1}),
//   D1 = coefficients of 2 M p' + C p: C on every coefficient plus, per harmonic n, on the
//        (a_n, b_n) pair of each DOF pair (cos row, sin row)
//          [ C           2 n omega M ]
//          [ -2 n omega M  C         ]
//        since p = a cos n theta + b sin n theta has p' = n omega (b cos n theta - a sin n theta).
// (1) is solved through its first-order form with z = [P; lambda P],
//   [ 0              I            ] z = lambda z,
//   [ -D2^-1 J    -D2^-1 D1       ]
// densely (Eigen's real EigenSolver): 2 n_dof (2H+1) eigenvalues. M must be invertible.
//
// Selection. The exact problem's exponents are defined modulo i omega: lambda + i k omega with
// p e^{-i k omega t} is the same perturbation. Of each such family the truncated eigenproblem
// keeps 2H + 1 members, and the ones whose eigenvectors reach the truncation edge (harmonic H) are
// the least accurate. We keep the 2 n_dof eigenvalues whose eigenvectors are most concentrated on
// the central harmonics: writing p(t) = sum_{k=-H..H} c_k e^{i k theta}
// (c_{+-n} = (a_n -+ i b_n) / 2), the centroid of each eigenvector is
//   kappa = sum_k k w_k / sum_k w_k,   w_k = sum over DOFs of |c_k|^2,
// and the 2 n_dof eigenvalues of smallest |kappa| are kept. This is the "symmetric eigenvector"
// criterion of Guillot, Lazarus, Thomas, Vergez & Cochelin, J. Comput. Phys. 416 (2020) 109477:
// members of a family differ by a shift of their eigenvector by k harmonics, so one member per
// Floquet exponent is centred (kappa ~ 0, or +-1/2, see below), and it is the member least
// affected by truncation. It was chosen over the classic criterion of Lazarus & Thomas,
// C. R. Mecanique 338 (2010) 510-517 (keep the eigenvalues of smallest |Im lambda|) because that
// one relies on imaginary parts alone: at period doubling two members of a family tie at
// |Im| = omega / 2, and a truncation-polluted member (eigenvector at the edge) may have a small
// imaginary part too; the eigenvector criterion looks at where the perturbation lives in the
// spectrum instead. It keeps a role as tie-break: centroids tie exactly for real eigenvectors
// (kappa = 0 identically) and for blocks the truncation decouples (H = 1 with an odd
// nonlinearity: the a_0 block is a kappa = 0 pair of its own, next to the real exponents of the
// (a_1, b_1) block on the branch between two folds); among tied centroids the smallest |Im| wins.
// The returned exponents are therefore
// the centred representatives, not reduced to |Im| <= omega / 2 (for a linear oscillator
// -zeta w_n +- i w_d exactly, whatever omega).
//
// Real negative multipliers (period doubling): the perturbation is then e^{mu t} r(t) with r
// real and T-antiperiodic, whose representatives mu + i omega / 2 and mu - i omega / 2 are each
// other's complex conjugate and both have |kappa| = 1/2. Such a conjugate pair stands for ONE
// multiplier, so when one of them is kept its twin is skipped (the one with Im > 0 is reported);
// otherwise two real negative multipliers would be reported as one counted twice.
//
// Floquet multipliers rho = exp(lambda T); the solution is (linearly) stable when every |rho| <= 1,
// i.e. max Re lambda <= 0. The kind of a loss of stability follows from the exponent of largest
// real part, its imaginary part reduced modulo omega: 0 (real multiplier > 1: a fold of the
// response curve, or a branch point), omega / 2 (multiplier < -1: period doubling), otherwise a
// complex pair (Neimark-Sacker, quasi-periodic response).
//
// Forces depending on the velocity, f_nl(q, q'): the perturbed velocity e^{lambda t}
// (lambda p + p') enters f_nl through df_nl/dv; J (= dR/dX, with v = omega Q' X) carries the p'
// part, and the lambda p part adds to D1 the harmonic-balance derivative of the force
// coefficients with respect to the velocity's coefficients, Jv = dF_nl/dV (per DOF pair
// P diag(df/dv) Q, the AFT of df/dv the way df/du enters J):
//   (lambda^2 D2 + lambda (D1 + Jv) + J) P = 0.
// Pass Jv (ElementHarmonicBalance::velocity_jacobian), or use the overload on an
// ElementHarmonicBalance that forms J and Jv itself. For
// hysteretic (friction) forces the Jacobian is that of the force's harmonic description and the
// result is the common engineering approximation, not a proven Floquet analysis.
#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm {

struct HillOptions {
  /// Stable when max Re lambda <= stability_tolerance * omega, i.e. every Floquet multiplier
  /// |rho| <= exp(2 pi stability_tolerance). Dimensionless, >= 0.
  double stability_tolerance = 1e-6;
  /// An exponent whose Im lambda, reduced modulo omega, lies within kind_tolerance * omega of 0
  /// is real (Fold), within it of omega / 2 a period-doubling one; the latter also decides which
  /// conjugate pairs are period-doubling twins (see the header comment). Loose by default:
  /// multipliers near -1 are poorly separated at finite H, and a complex pair within this band
  /// of the negative real axis is reported as period doubling. Dimensionless, in (0, 0.25).
  double kind_tolerance = 1e-3;

  /// Throws InputError naming every out-of-range field.
  void validate() const;
};

struct FloquetResult {
  enum class Instability {
    None,            ///< stable
    Fold,            ///< a real multiplier > 1 (real exponent > 0)
    PeriodDoubling,  ///< a real multiplier < -1 (Im lambda = omega / 2 modulo omega)
    NeimarkSacker    ///< a complex pair of multipliers outside the unit circle
  };

  Status status = Status::Failed;
  std::string message;  ///< empty when ok; otherwise what went wrong

  /// The 2 n_dof selected exponents lambda [1/s] (perturbation ~ e^{lambda t} p(t)), ordered by
  /// decreasing real part (then decreasing imaginary part).
  Eigen::VectorXcd exponents;
  /// rho = exp(lambda 2 pi / omega), same order.
  Eigen::VectorXcd multipliers;
  /// |kappa| (harmonic centroid, see the header comment) of each selected eigenvector.
  Eigen::VectorXd centroids;
  /// Smallest |kappa| of a rejected eigenvector minus the largest of a selected one (twins
  /// excluded): near 1 when the centroids alone decide, 0 when the |Im| tie-break did, small
  /// when two family members share the centre (Im lambda near omega / 2, multipliers near -1).
  double sorting_gap = std::numeric_limits<double>::quiet_NaN();

  double max_real_part = std::numeric_limits<double>::quiet_NaN();  ///< of `exponents` [1/s]
  bool stable = false;  ///< max_real_part <= stability_tolerance * omega
  Instability kind = Instability::None;

  std::string brief_report() const;
};

/// Floquet exponents of the periodic solution whose harmonic-balance Jacobian is J (dR/dX,
/// size n_dof (2H+1), layout of harmonic_balance.hpp) for the mass and damping matrices M, C
/// (n_dof x n_dof, M invertible), `harmonics` = H and fundamental frequency omega > 0 [rad/s].
/// Keeps no reference. Throws InputError on inconsistent sizes, H < 0, omega <= 0, a singular
/// M or invalid options; a failed eigen-solve (non-finite J) is returned as Status::Failed.
/// Cost: one dense non-symmetric eigen-solve of size 2 n_dof (2H+1), with eigenvectors.
FloquetResult hill_stability(const Eigen::MatrixXd& J, const Eigen::MatrixXd& M,
                             const Eigen::MatrixXd& C, int harmonics, double omega,
                             const HillOptions& options = {});

/// The same with velocity-dependent forces: Jv = dF_nl/dV (n_dof (2H+1) square, or empty for
/// none) is added to the first-order term D1 (see the header comment). InputError also for a Jv
/// of another size.
FloquetResult hill_stability(const Eigen::MatrixXd& J, const Eigen::MatrixXd& Jv,
                             const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, int harmonics,
                             double omega, const HillOptions& options = {});
/// Hill stability of the solution X of `hb` at omega, its elements' velocity dependence included:
/// J = dR/dX and Jv = hb.velocity_jacobian(X, omega) with the system's M and C. Cost: one
/// linearization, one AFT of df/dv per velocity-dependent element and the eigen-solve.
FloquetResult hill_stability(const ElementHarmonicBalance& hb, const Eigen::VectorXd& X,
                             double omega, const HillOptions& options = {});
/// The kind of instability an exponent lambda with Re lambda > 0 stands for at frequency omega:
/// Fold when Im lambda, reduced modulo omega, is within kind_tolerance omega of 0, period
/// doubling when within it of omega / 2, Neimark-Sacker otherwise (see the header comment).
FloquetResult::Instability instability_kind(std::complex<double> lambda, double omega,
                                            double kind_tolerance);

/// Fold-type instability along a response curve traced by arc length from a stable start
/// (e.g. a forced response from a frequency below its resonances): at each turning point of the
/// frequency (d omega / ds changes sign) one real Floquet multiplier crosses +1 (Seydel,
/// "Practical Bifurcation and Stability Analysis", 3rd ed., Springer (2010), ch. 7), so the
/// points after an odd number of turning points are unstable (the jump phenomenon's middle
/// branch). Returns 1 per such point of `omega` (the curve's frequencies in order), 0 otherwise.
/// Needs no Jacobian, so it holds for hysteretic forces too; it does not see period doubling or
/// Neimark-Sacker losses of stability, nor a start that is already unstable.
std::vector<char> fold_unstable(const std::vector<double>& omega);

/// "none", "fold", "period_doubling", "neimark_sacker".
const char* to_string(FloquetResult::Instability kind);

/// Hill stability of every point of a continuation of `hb` (its Jacobian at each point, its M
/// and C): one FloquetResult per point, in order.
std::vector<FloquetResult> stability_along(const HarmonicBalance& hb,
                                           const ContinuationResult& curve,
                                           const HillOptions& options = {});

}  // namespace geardyn::hbm
