#pragma once
// Hill stability of a periodic solution of a condensed harmonic balance (condensed.hpp): the
// Floquet exponents of the structure seen through its modal receptance, with the nonlinear
// forces linearised about the solution. The physical-form method (stability.hpp) needs the mass
// and damping matrices of every DOF; here the structure is known only by its modal receptance at
// the nonlinear coordinates, so the variational problem is written in modal coordinates.
//
// Perturbation dx(t) = e^{lambda t} sum_k c_k e^{i k w t} of the coordinates, k over the balanced
// harmonics -H..H (a harmonic whose receptance is empty -- the mean held at zero -- has c_k = 0).
// Component k responds at the complex frequency s_k = lambda + i k w through
//   c_k = -G_k(s_k) g_k,   G_k(s) = U_k diag(1 / (w_r^2 + 2 zeta_r w_r s + s^2)) V_k^H + R_k,
// the receptance of harmonic n = |k| continued to complex frequency (G_k(i n w) = H_n(n w)); for
// k < 0 the conjugate pattern (U, V, R conjugated: G_{-k}(conj s) = conj G_k(s)), for k = 0 the
// real part (columns [Re U, Im U]). g = J_c c is the force perturbation, J_c = T J_nl T^-1 the
// Jacobian of the forces' harmonic description dF_nl/dX taken to these complex coefficients
// (c_k = (a_k - i b_k) / 2, c_-k = (a_k + i b_k) / 2, c_0 = a_0). With modal coordinates eta,
// c = U eta - R g, so c = P eta with P = (I + R J_c)^-1 U, and per modal coordinate of block k
//   (s_k^2 + 2 zeta_r w_r s_k + w_r^2) eta_r + (V^H J_c P eta)_r = 0,
// i.e. with s_k = lambda + i k w the quadratic eigenproblem
//   lambda^2 eta + lambda diag(2 zeta_r w_r + 2 i k w) eta
//     + [diag(w_r^2 - k^2 w^2 + 2 i zeta_r w_r k w) + V^H J_c P] eta = 0,
// solved through its first-order form (dense, complex): 2 x (modes of all blocks) exponents.
// With every mode kept and no residual this is exactly the physical-form Hill problem written in
// modal coordinates and the complex Fourier basis (the same eigenvalues); the residual
// flexibility enters as a quasi-static correction of the coupling (the dropped modes' dynamics
// are not represented, as in the balance itself).
//
// Selection. When every balanced harmonic has the same real modes (an ordinary structure, or a
// cyclic one at a standing nodal diameter), the components are shifts of one another and each
// Floquet exponent appears once per component (lambda - i k omega); as in stability.hpp one
// representative per family is kept, the eigenvector most concentrated on the central
// components (modal centroid), ties by the smallest |Im|: 2 x modes exponents, the ones
// least affected by the truncation. With complex (travelling-wave) shapes or a different pattern
// per harmonic (a cyclic sector whose harmonic n carries nodal diameter n h) a shift does not map
// one perturbation onto another, and all exponents are returned. The verdict uses the largest
// real part. Same conventions as stability.hpp for multipliers, tolerance and the kind of
// instability. For hysteretic (friction) forces the Jacobian is that of the force's harmonic
// description: the common engineering approximation, not a proven Floquet analysis.
//
// Limitation found on the damper-ring example (not wired into damper_ring_response for that
// reason): with stiff friction contacts on a cyclic sector's travelling-wave modes, the
// harmonic-description Jacobian of a stick-slip contact acts on perturbations far from the
// response frequency as a circulatory (non-symmetric) stiffness; the Hill matrix then has
// flutter-type exponents with Re lambda ~ 0.3 omega at |Im lambda| ~ 10 omega, beyond the modes
// kept, wherever the contacts slip. The same approximation is adequate near the response
// frequency and for the validated cases below; a friction-aware check of the damped curve needs
// the perturbation marched through the stick-slip law in time (a monodromy matrix of the modal
// model), the next step.
//
// Cost: one dense complex LU of n_coordinates x (balanced blocks) for P and one dense complex
// eigenvalue solve of 2 x (modes of all blocks), with eigenvectors when families are selected:
// O(n^3) in both, milliseconds for tens of coordinates and modes.
#include <Eigen/Dense>

#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::hbm {

/// Floquet exponents of the solution X of `hb` at frequency omega > 0 (see above):
/// `exponents` (selected as above) by decreasing real part, `centroids` empty, `sorting_gap`
/// NaN. Period-doubling twins are not merged (a real negative multiplier may appear twice).
/// Throws InputError on a wrong size of X, omega <= 0 or invalid options; a failed eigen-solve
/// (non-finite Jacobian) is returned as Status::Failed.
FloquetResult condensed_hill_stability(const CondensedHarmonicBalance& hb, const Eigen::VectorXd& X,
                                       double omega, const HillOptions& options = {});

/// Unknowns of the dense LU of condensed_hill_stability (n_coordinates x balanced blocks), to
/// decide whether evaluating it at every point of a curve is affordable.
int condensed_hill_size(const CondensedHarmonicBalance& hb);

}  // namespace geardyn::hbm
