#pragma once
// The condensed form of the nonlinear frequency response (coordinates = "condensed";
// docs/theory.md §19): the harmonic balance solved on the relative coordinates of the placed
// nonlinear elements only, u = B q (B: the elements' placement rows stacked, n_c rows), the
// linear structure entering through its receptance at those coordinates (hbm/condensed.hpp):
//   u_n = x_lin,n(n w) - H_n(n w) f_n,   n = 0..H,
//   H_n(W) = B Phi diag(1 / d_r(W)) Phi^T B^T + R_res,   d_r(W) = w_r^2 - W^2 + 2 i zeta_r w_r W,
//   R_res = B (K^+ - Phi diag(1 / w_r^2) Phi^T) B^T   (residual flexibility of the modes left out),
//   x_lin,n(W) = B Phi diag(1 / d_r(W)) Phi^T F_n + B (K^+ - Phi diag(1/w_r^2) Phi^T) F_n,
// with Phi the n_modes lowest undamped mass-normalised modes at the reference speed, F_n the
// excitation of harmonic n (the analysis's named forces at n = 1, its mean loads at n = 0) and
// the sensors recovered the same way (rows S instead of B). The Newton system has n_c (2H + 1)
// unknowns however many DOFs the model has; continue_in_frequency solves it by GMRES with the
// Woodbury preconditioner of condensed.hpp.
//
// Residual flexibility. K^+ restricted to the modes left out is computed from one sparse
// factorisation of the shifted K - sigma M, sigma = -1e-4 w_m^2 (w_m the highest mode kept):
// the load is deflated against the kept modes, L_d = (I - M Phi Phi^T) L, and K X = L_d solved by
// the fixed point (K - sigma M) X_{k+1} = L_d - sigma M X_k (with X_k M-orthogonalised against
// Phi), which contracts by |sigma| / (w_{m+1}^2 - sigma) < 1e-4 per step on the modes left out:
// exact to round-off in a few steps, for a regular K and for a singular one alike (free torsion,
// a free-free rotor), provided the rigid-body modes are among those kept (InputError at n_modes
// otherwise). With the residual term the condensation is exact for the static part (H_0 = B K^-1
// B^T for a regular K); the dynamic error of each mode left out is the relative (W / w_r)^2 of
// its quasi-static term, so the modes kept should reach well above H x the highest fundamental.
//
// Mean (harmonic 0) of a structure with rigid-body modes (w_r = 0, below 1e-8 w_m^2): inertia
// relief -- the rigid-body part of the mean loads (external and nonlinear) is balanced by a
// uniform acceleration, the mean rigid-body displacement is held at zero, and the elastic part is
// exact (the rigid modes are left out of H_0, kept in H_n for n >= 1 where d_r = -W^2).
//
// Damping: modal damping ratios from the diagonal of Phi^T C Phi (Rayleigh, modal, bearing and
// coupling dampers alike), 2 zeta_r w_r = (Phi^T C Phi)_rr. Exact for proportional damping; for
// non-proportional damping the coupling between modes is left out (a note reports its largest
// relative size |c_rs| / sqrt(c_rr c_ss)); the damping of rigid-body modes is left out. Gyroscopic
// terms (skew, zero diagonal) at a reference speed, a hysteretic loss factor (K_loss) and a
// non-symmetric stiffness (cross-coupled bearings) are not diagonal in the modes: InputError
// (use the modal or physical form).
//
// Reference: the receptance condensation of friction-damping codes, E. P. Petrov & D. J. Ewins,
// "Analytical formulation of friction interface elements for analysis of nonlinear multi-harmonic
// vibrations of bladed disks", J. Turbomach. 125 (2003) 364-371; M. Krack & J. Gross, "Harmonic
// Balance for Nonlinear Vibration Problems", Springer (2019), sec. 3.4.
#include <Eigen/Dense>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/nonlinear_elements.hpp"
#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::analyses {

/// What the physical path of run_nonlinear_response has built and the condensed form reuses.
struct NonlinearProblem {
  const fe::LinearSystem& system;
  const std::vector<BuiltNonlinearElement>& elements;
  const NonlinearCoordinates& modes;  ///< the n_modes lowest modes (modal form of the same K)
  const Eigen::MatrixXd& excitation;  ///< n_eq x 3: a_0, a_1, b_1 per equation
  const SensorRows& sensors;
};

/// Switches of the condensed form beyond the model file (for validation).
struct CondensedFormOptions {
  /// false: no residual flexibility (the modal sum only: the modal form with diagonal damping).
  bool residual_flexibility = true;
};

/// The receptances of harmonics 0..H on the elements' stacked coordinates (see the header
/// comment), the sensors' recovery rows included. InputError (located by `context`) for a
/// structure the condensed form cannot represent; NumericalError when the shifted stiffness
/// cannot be factorised or the residual flexibility does not converge. `notes` receives what
/// was done (modes, shift, rigid-body modes, damping coupling).
std::vector<hbm::ModalReceptance> condensed_receptances(const NonlinearProblem& problem,
                                                        const NonlinearResponseSettings& settings,
                                                        const CondensedFormOptions& options,
                                                        const Context& context,
                                                        std::vector<std::string>& notes);

/// The response in the condensed form (settings.coordinates = Condensed). Same result layout as
/// run_nonlinear_response (sensor coefficients per point, element energy and regimes, loops,
/// turning points, stability by folds or by condensed Hill). InputError for parameter other than
/// frequency / force_level and for stability = "monodromy".
NonlinearResponseResult run_nonlinear_condensed(const NonlinearProblem& problem,
                                                const NonlinearResponseSettings& settings,
                                                const Context& context,
                                                const CondensedFormOptions& options = {});

// ---- Shared with run_nonlinear_response (defined in nonlinear_response.cpp) ----------------

/// Moves the last point past `end` onto it (interpolation and a Newton correction at `end`).
void land_on_end(const hbm::HarmonicSystem& system, double end, double tolerance,
                 std::vector<hbm::ContinuationPoint>& points);
/// Turning points of the parameter p along the curve, clusters closer than `merge` merged.
std::vector<int> turning_points(const std::vector<double>& p, double merge);
/// Unstable after an odd number of turning points, from a stable start.
std::vector<char> unstable_after(const std::vector<int>& turns, std::size_t points);
/// Records point i's Floquet verdict into r.
void record_floquet(const hbm::FloquetResult& f, std::size_t i, NonlinearResponseResult& r);
/// The point of largest sensor RMS (-1 without points).
int largest_point(const NonlinearResponseResult& r);
/// A curve that ended before the end of its range: status NotConverged with the reason.
void mark_ended_early(const hbm::ContinuationResult& curve, NonlinearResponseResult& r);

}  // namespace geardyn::analyses
