#pragma once
// Node-to-node friction contact with a variable normal load (docs/theory.md §8) for the alternating
// frequency-time method of harmonic balance (docs/theory.md §8): the periodic contact forces of one
// period of prescribed relative motion, with their exact derivative with respect to the Fourier
// coefficients of that motion (an analytic AFT Jacobian). Also a unilateral (gap) spring.
//
// Local contact coordinates w = [v, u_1, (u_2)], relative displacements measured from the
// preloaded static equilibrium: v the normal approach (v > 0 presses the surfaces together),
// u the tangential slip vector (one component for a 2D contact, two for a 3D contact). At every
// time sample theta_j = 2 pi j / n of the period:
//
//   normal      N_j  = max(N_0 + k_n v_j, 0)
//   predictor   T*_j = T_{j-1} + k_t (u_j - u_{j-1})
//   lift-off    N_j = 0:              T_j = 0
//   slip        |T*_j| >= mu N_j:     T_j = mu N_j T*_j / |T*_j|   (radial return)
//   stick       otherwise:            T_j = T*_j
//
// The element adds the generalized force [N - N_0, T] to the residual of harmonic_balance.hpp:
// the preload N_0 is balanced by the static load that produces it (e.g. the centrifugal load of a
// damper ring pressing on its groove), so w = 0 is an equilibrium and only the change of the
// normal force enters the dynamic balance. With k_n = 0 the normal load is the constant N_0 and
// the tangential law is the Jenkins element (jenkins.hpp) with slip force mu N_0, in one
// direction, or its isotropic 2D extension (a circular slip limit) in two.
//
// History: the march starts stuck about the mean tangential position, T = k_t (u_0 - mean(u)),
// returned to the friction limit like any predictor, and marches whole periods until the state
// (T and its gradient) at the start of a period repeats (ContactMarchOptions). A 1D loop with
// constant N that slips closes after one period; with a variable normal load or 2D slip the
// slider's memory fades geometrically (by the factor mu N / |T*| of each 2D slip sample) and the
// loop may need several periods. A loop that never slips is the linear spring k_t (u - mean(u)).
//
// Jacobian: the gradient of T with respect to all coefficients of w is propagated through the
// march (dT*_j = dT_{j-1} + k_t (Q_j - Q_{j-1}) du, Q the sampling matrix), through
//   slip      dT = mu dN t + (mu N / |T*|) (I - t t^T) dT*,   t = T* / |T*|,   dN = k_n dv,
// and to zero at lift-off; the force coefficients are P T (P the projection), so
// d coefficients / d w = P dT / dw exactly for the march performed.
// References: Yang, Chu & Menq, "Stick-slip-separation analysis and non-linear stiffness and
// damping characterization of friction contacts having variable normal load", J. Sound Vib. 210
// (1998) 461-481 (the 2D law); Sanliturk & Ewins, "Modelling two-dimensional friction contact and
// its application using harmonic balance method", J. Sound Vib. 193 (1996) 511-523 (2D slip);
// Simo & Hughes, "Computational Inelasticity", Springer (1998) (the return-mapping algorithm).
#include <Eigen/Dense>
#include <limits>
#include <vector>

#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"

namespace geardyn::hbm {

struct FrictionContact {
  int tangential_directions = 1;      ///< 1: 2D contact (v, u_1); 2: 3D contact (v, u_1, u_2)
  double normal_stiffness = 0.0;      ///< k_n [N/m], finite >= 0 (0: constant normal load N_0)
  double tangential_stiffness = 0.0;  ///< k_t [N/m], finite > 0
  double friction_coefficient = 0.0;  ///< mu [-], finite >= 0
  double normal_preload = 0.0;        ///< N_0 [N], finite >= 0, the normal force at w = 0
};

/// How the period is marched to its steady state.
struct ContactMarchOptions {
  int max_periods = 16;  ///< periods marched at most, >= 1
  /// The loop is closed when the tangential force at the start of consecutive periods differs by
  /// at most closure_tolerance * max(mu max_j N_j, k_t max_j |u_j - mean(u)|, DBL_MIN) in every
  /// component, and its gradient by closure_tolerance * max(k_t, mu k_n); finite >= 0.
  double closure_tolerance = 1e-12;
};

enum class ContactState { Stick, Slip, LiftOff };

struct ContactResponse {
  /// Fourier coefficients of the generalized force, coordinate-major like w:
  /// [P (N - N_0); P T_1; (P T_2)], size (1 + directions) (2H + 1).
  Eigen::VectorXd coefficients;
  /// d coefficients / d w (square, coefficients.size()).
  Eigen::MatrixXd jacobian;
  /// Samples over the kept period, n_time x (1 + directions): column 0 the total normal force
  /// N_j >= 0 (preload included), then the tangential force components T_j [N].
  Eigen::MatrixXd force;
  std::vector<ContactState> state;  ///< per sample of the kept period
  double stick_fraction = std::numeric_limits<double>::quiet_NaN();     ///< share of the samples
  double slip_fraction = std::numeric_limits<double>::quiet_NaN();      ///< share of the samples
  double lift_off_fraction = std::numeric_limits<double>::quiet_NaN();  ///< share of the samples
  /// Closed-loop integral of T . du over the kept period, trapezoidal rule over the samples [J].
  /// (The normal force is elastic and does no net work over a period.)
  double energy_per_cycle = std::numeric_limits<double>::quiet_NaN();
  bool loop_closed = false;  ///< the start state repeated within ContactMarchOptions
  int periods_marched = 0;   ///< the kept period is the last one marched
  /// Largest start-of-period difference of the last period, relative to its scale (see
  /// ContactMarchOptions::closure_tolerance).
  double closure_error = std::numeric_limits<double>::quiet_NaN();
};

/// The steady periodic forces of `contact` for the relative motion with Fourier coefficients
/// `w` = [v; u_1; (u_2)] (each block basis.size(), HarmonicBasis layout). Throws InputError for
/// an invalid contact, options or size of w. A loop that does not close within max_periods is
/// returned from the last period with loop_closed = false.
ContactResponse friction_contact_response(const FrictionContact& contact,
                                          const HarmonicBasis& basis,
                                          const Eigen::Ref<const Eigen::VectorXd>& w,
                                          const ContactMarchOptions& options = {});

/// Throws InputError naming the first invalid field of `contact`.
void validate(const FrictionContact& contact);

struct UnilateralResponse {
  Eigen::VectorXd force;         ///< f(theta_j) = k max(q_j - gap, 0) [N], j = 0 .. n - 1
  Eigen::VectorXd coefficients;  ///< Fourier coefficients of f (HarmonicBasis layout)
  Eigen::MatrixXd jacobian;      ///< d coefficients / d coefficients(q) = P diag(slope) Q
  double contact_fraction = std::numeric_limits<double>::quiet_NaN();  ///< share with q_j > gap
};

/// A spring of stiffness k (finite > 0) that acts only once the displacement q exceeds `gap`
/// (finite; gap < 0: preloaded by k |gap| at q = 0): f = k max(q - gap, 0), for the motion with
/// Fourier coefficients `q`. The slope at q_j == gap is taken as 0 (open).
UnilateralResponse unilateral_spring_response(double stiffness, double gap,
                                              const HarmonicBasis& basis,
                                              const Eigen::Ref<const Eigen::VectorXd>& q);

/// `contact` acting on the system DOFs coordinates[0] (normal, v) and coordinates[1 ..]
/// (tangential u_1, u_2) of the harmonic balance unknowns (DOF-major, harmonic_balance.hpp):
/// those DOFs must already be the contact's local relative coordinates. Its force coefficients
/// are added to those DOFs and its Jacobian to the corresponding blocks. Throws InputError at
/// construction for an invalid contact or coordinates (count 1 + directions, >= 0, distinct),
/// and when called with an X too short for the coordinates. The march uses the default
/// ContactMarchOptions; an unclosed loop (only 2D slip that barely exceeds the friction limit
/// converges slowly) enters with its last period.
NonlinearForce friction_contact_force(std::vector<int> coordinates, FrictionContact contact);

/// The unilateral spring f = k max(q_dof - gap, 0) on one DOF (unilateral_spring_response).
/// Throws InputError at construction for dof < 0 or an invalid stiffness or gap.
NonlinearForce unilateral_spring(int dof, double stiffness, double gap);

}  // namespace geardyn::hbm
