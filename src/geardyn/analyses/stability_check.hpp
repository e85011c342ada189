#pragma once
// Stability check of the steady-state analyses (unbalance, harmonic): a steady state computed
// from D(w) X = F exists for any system whose D(w) is regular, stable or not, but an unstable
// machine never reaches it. Before such a result is called ok, the least-damped complex modes of
//   M q'' + (C(W) + W G + C_modal) q' + K(W) q = 0
// at the analysis's speed W are computed with the quadratic eigen-solver (eig/quadratic_eigen)
// and every mode with Re(lambda) > 0 is reported.
//
// Which modes (the rule): the modes of smallest |lambda| (the solver's automatic target), as
// many as needed so that the highest natural frequency computed is at least
// kBandMargin x the highest frequency the analysis excites (unbalance: largest order x speed;
// harmonic: frequency_stop), and at least kMinModes; the count grows until that holds, every
// mode of the system is computed, or kMaxModes is reached (the cost of one Arnoldi solve grows
// with the modes asked for; a band that needs more is rare for rotors and the note then says
// up to which frequency the check holds). Modes above the highest one computed are not checked.
//
// Solver: on models above 30 DOFs the scan projects every speed onto one basis of undamped
// modes at rest, kept and enriched from speed to speed (eig/projected_quadratic.hpp; every mode
// it returns is checked at full size); a speed where it cannot certify every mode is solved
// again by solve_quadratic (Arnoldi shift-invert), counted and stated in the note; after two
// such speeds in a row the scan gives the projection up (each failure costs several enrichment
// rounds on top of the full solve; e.g. the double roots at 0 of free axial and torsional motion
// are defective and their Ritz vectors converge slowly).
//
// Verdict: a mode (lambda, x) is unstable when both
//  (1) its growth rate Re(lambda) exceeds kGrowthTolerance x (the highest natural frequency
//      checked): a mode growing slower needs 1e6 radians of the highest frequency to grow by e,
//      less than any physical damping can be trusted to; and
//  (2) the sign of Re(lambda) is not round-off: the pair moved onto the imaginary axis,
//      (i Im lambda, x), has a normwise backward error (Tisseur, Linear Algebra Appl. 309
//      (2000) 339-361, Thm 1) eta_0 = ||P(i Im lambda) x|| / ((|lambda|^2 ||M|| + |lambda| ||D||
//      + ||K||) ||x||) above eta_tol = max(kBackwardErrorFactor x eta, kRoundoffBackwardError),
//      eta the backward error of the computed pair. If eta_0 <= eta_tol, the pencil perturbed
//      by eta_tol relative has the neutral eigenvalue i Im lambda: the data at the solver's
//      accuracy cannot tell the mode from a neutral one. To first order this is the perturbation
//      bound |delta lambda| <= eta_tol (|lambda|^2 ||M|| + |lambda| ||D|| + ||K||) ||x||^2 /
//      |x^* P'(lambda) x| on Re(lambda) (Tisseur, Thm 5, with y = x: exact for undamped
//      gyroscopic pencils, Hermitian on the imaginary axis), and it also holds at double roots
//      (lambda = 0 of free axial or torsional motion), where P'(0) x = 0, the first-order bound is
//      void and round-off of ||K|| eta splits the root by sqrt(eta ||K|| / ||M||): on fine meshes,
//      ||K|| / ||M|| is far above (the highest frequency checked)^2, so rule (1) alone called
//      such roots growing (issue 19: the ROSS comparison rotor, undamped, was "unstable").
//      An undamped gyroscopic rotor (D = W G, G skew) thus is never called unstable by
//      round-off, while a real instability of growth rate g has eta_0 ~ g |x^* P'(lambda) x| /
//      (scale ||x||^2): it is reported when that exceeds 10 eta, i.e. when g is beyond the
//      first-order error bound of the computed Re(lambda) (e.g. the cross-coupled bearing
//      instabilities of the tests, damping ratios -1e-3 to -0.06, are far beyond it).
//
// Energy certificate (scans that allow it: unbalance): most rotors need no eigen-solve at all.
// With M positive definite, K symmetric positive semi-definite, G skew-symmetric and the
// symmetric part of the damping C_s >= -tau M, the energy E = (q'^T M q' + q^T K q) / 2 obeys
// dE/dt = -q'^T C_s q' <= tau q'^T M q' <= 2 tau E (the gyroscopic forces do no work), so a mode
// q = Re(x e^(lambda t)) with E != 0 has Re(lambda) <= tau: no mode grows faster than tau
// (Lyapunov's direct method; for tau = 0 the theorem of Kelvin, Tait and Chetaev, e.g.
// L. Meirovitch, Methods of Analytical Dynamics, McGraw-Hill 1970, ch. 6). With tau =
// kGrowthTolerance x kBandMargin x band_top, the growth rule (1) can call no mode unstable, so
// the verdict "stable" holds at every speed of the list without solving. The checks: exact
// symmetry of K and skew-symmetry of G (to 1e-13 in the Frobenius norm); no speed-dependent
// bearing (their K(W), C(W) would have to be checked at every speed); modal damping
// coefficients >= 0; Cholesky factorisations of M and of C_s + tau M succeed (positive
// definite); and K positive semi-definite: its lowest eigenvalues (M-orthogonal to the rigid-
// body motions K leaves at rest, eig/rigid_body.hpp) are > 0. Cross-coupled bearings, negative
// stiffness or damping, follower forces fail a check, and the scan solves as before.
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::analyses {

struct StabilityMode {
  int mode = 0;                     ///< rank by natural frequency among the modes checked (1..)
  std::complex<double> eigenvalue;  ///< lambda [rad/s], Im >= 0
  double frequency = 0.0;           ///< natural frequency |lambda| [rad/s]
  double damping_ratio = 0.0;       ///< -Re(lambda) / |lambda|
};

/// The verdict at one speed.
struct StabilityAtSpeed {
  double speed = 0.0;  ///< [rad/s]
  bool stable = true;  ///< no checked mode grows
  int modes_checked = 0;
  double covered = 0.0;        ///< highest natural frequency checked [rad/s]
  bool band_covered = true;    ///< covered >= the band asked for (false: every mode was computed
                               ///< and the system has none higher, also fine; see message)
  StabilityMode least_damped;  ///< smallest damping ratio among the modes checked
  std::vector<StabilityMode> unstable;            ///< growing modes, by frequency
  std::vector<std::complex<double>> eigenvalues;  ///< every mode checked, Im >= 0, by |lambda|
  Status solver_status = Status::Ok;              ///< of the eigen-solve
  std::string solver_message;
};

constexpr double kBandMargin = 2.0;
constexpr int kMinModes = 24;  // one solve covers twice the top excitation of most rotors
constexpr int kMaxModes = 150;
constexpr double kGrowthTolerance = 1e-6;
/// eta_tol = max(kBackwardErrorFactor x the mode's backward error, kRoundoffBackwardError):
/// 10 covers the residual's own evaluation in floating point and the first-order nature of the
/// bound; 1e-15 (about 5 unit round-offs) is the floor of any residual evaluated in double
/// precision. Measured (48-element ROSS rotor, Arnoldi): eta 3e-16 to 2e-13 for the roots at 0,
/// 3e-12 to 1e-9 for the elastic modes; moving them onto the axis leaves eta unchanged to 1 %.
constexpr double kBackwardErrorFactor = 10.0;
constexpr double kRoundoffBackwardError = 1e-15;

/// Rule (2) of the verdict: false when (i Im lambda, x) has a backward error for `pencil` within
/// max(kBackwardErrorFactor x `backward_error`, kRoundoffBackwardError), i.e. when Re(lambda) > 0
/// is within the round-off of the solve.
/// Tisseur's normwise backward error of (lambda, x) for `pencil` (as backward_errors()).
double axis_backward_error(const eig::QuadraticPencil& pencil, std::complex<double> lambda,
                           const Eigen::VectorXcd& x);
bool certified_growing(const eig::QuadraticPencil& pencil, std::complex<double> lambda,
                       const Eigen::VectorXcd& x, double backward_error);

/// The verdict at `speed` [rad/s], checking the modes up to kBandMargin x `band_top` [rad/s].
/// `n_modes_hint` (in/out): the mode count to start with; on return the count that sufficed.
StabilityAtSpeed check_stability(const fe::LinearSystem& system, double speed, double band_top,
                                 int* n_modes_hint = nullptr);

/// The eigen-solver of a scan (defined in stability_check.cpp): the projection kept from speed
/// to speed with the full solver as fallback. Not thread-safe.
class StabilitySolver;
/// As above, through `solver` (nullptr: solve_quadratic).
StabilityAtSpeed check_stability(const fe::LinearSystem& system, double speed, double band_top,
                                 int* n_modes_hint, StabilitySolver* solver);

/// The verdicts over a list of speeds (any order). Up to kMaxSampledSpeeds speeds every one is
/// checked; beyond that an evenly spread subset of the sorted list (ends included) is, and
/// between two sampled speeds whose verdicts differ the first speed of the list with the other
/// verdict is found by bisection on the list, then the onset itself by bisection on the speed
/// to kOnsetTolerance (relative). The other speeds take the verdict of the sampled speeds around
/// them (a stability window narrower than the sample spacing can be missed: the note says so).
struct StabilityScan {
  double band_top = 0.0;                 ///< highest excitation frequency [rad/s]
  std::vector<bool> stable;              ///< per speed of the list, in its order
  std::vector<bool> checked;             ///< per speed: its own eigen-solve (false: inferred)
  std::vector<StabilityAtSpeed> solves;  ///< every solve, sorted by speed
  /// Onsets: speeds [rad/s] where the verdict changes, refined; with the verdict above them.
  struct Change {
    double speed = 0.0;
    bool stable_above = false;
  };
  std::vector<Change> changes;
  int n_solves = 0;
  bool subsampled = false;
  int projected_solves = 0;          ///< solves certified by the projection
  int projection_fallbacks = 0;      ///< solves the projection could not certify (full solver)
  std::string first_fallback;        ///< why, at the first of them
  bool projection_given_up = false;  ///< two failures in a row: the full solver for the rest
  bool certified = false;            ///< stable everywhere by the energy certificate (no solves)
  double certified_growth = 0.0;     ///< tau of the certificate [1/s]
  std::string not_certified;         ///< why the certificate did not apply (when it was tried)

  bool all_stable() const;
  /// The least-damped solve among the unstable ones (nullptr: none).
  const StabilityAtSpeed* worst() const;
};

constexpr int kMaxSampledSpeeds = 41;
constexpr double kOnsetTolerance = 1e-4;

/// `band_top`: highest excitation frequency of the analysis [rad/s] (the same at every speed).
/// `project`: through the projection (models above 30 DOFs); false: the full solver at every
/// speed (the reference). `certify`: try the energy certificate first (header comment); when it
/// holds, no speed is solved (solves stays empty).
StabilityScan scan_stability(const fe::LinearSystem& system, const std::vector<double>& speeds,
                             double band_top, bool project = true, bool certify = false);

/// The energy certificate of the header comment with growth bound `tau` [1/s]: an empty string
/// when it holds, otherwise the first check that failed.
std::string energy_certificate(const fe::LinearSystem& system, double tau);

/// "mode 4 (95.75 Hz, damping ratio -0.052)".
std::string describe(const StabilityMode& m);

/// The message of Status::Unstable for a scan: the unstable speed range(s) in rpm and the
/// fastest-growing mode at the least-damped unstable speed. Empty when every speed is stable.
std::string unstable_message(const StabilityScan& scan);

/// The note on the check: the rule, modes checked, band, solves, least damping ratio, and the
/// unstable range(s).
std::string stability_note(const StabilityScan& scan);

}  // namespace geardyn::analyses
