#pragma once
// A gear mesh with backlash and time-varying stiffness as a nonlinear element of harmonic balance
// (docs/theory.md §8; issue #18, `nonlinear_elements`): the single-coordinate mesh law of the
// gear-dynamics literature, memoryless, evaluated by the AFT of PointwiseElement.
//
// Coordinate (n = 1): delta [m], the approach of the teeth along the line of action, positive
// closing the drive flank (the convention of elements/gear_mesh_contact.hpp). The phase theta of
// the balance is the phase of the MESH cycle: the fundamental omega of the harmonic balance is
// the mesh frequency (teeth x shaft speed), one period of theta is one mesh cycle, and the
// excitation of a gear pair (the unloaded transmission error, the stiffness variation) lives on
// its harmonics.
//
// Law, with the mesh stiffness k(theta) > 0, the unloaded transmission error e(theta), the total
// backlash b >= 0 along the line of action and the viscous mesh damping c >= 0:
//   drive flank   p   = delta - e(theta)          > 0:   f = k p + c p'
//   back flank    p_b = -(delta - e(theta)) - b   > 0:   f = -(k p_b + c p_b') = k (p + b) + c p'
//   otherwise (contact loss, inside the backlash):       f = 0,
// with the rates p' = delta' - omega e'(theta) (e' = de/dtheta; d/dt = omega d/dtheta) and
// p_b' = -p'. The back flank follows the drive flank's unloaded TE shifted by the backlash and
// has its stiffness at the same phase (as in gear_mesh_contact.hpp); b = +infinity: no back
// flank. The damping acts in contact only and is not clipped: k p + c p' may be negative for an
// instant while the teeth separate (the law of the references below). A phase exactly at p = 0
// counts as open.
// Tangents: df/ddelta = k, df/ddelta' = c in contact, 0 open. The dependence on omega other than
// through delta' (PointwiseElement::pointwise_omega_derivative) is df/domega = -c e'(theta) in
// contact: it is zero without damping (f = k p at fixed delta and theta does not involve omega)
// or with a constant e.
//
// Tables: k and e are given over one mesh cycle on a uniform grid theta_i = 2 pi i / N
// (i = 0 .. N - 1, periodic), N >= 1 (N = 1: a constant), and interpolated LINEARLY and
// periodically. Linear interpolation was chosen over a Fourier series of the table because it
// keeps k > 0 and the table's extremes for any table (the near-rectangular stiffness of a spur
// mesh makes a trigonometric interpolant ring and undershoot), and because it is the
// interpolation of elements/gear_mesh_contact.hpp, so the two elements agree on a map. e' is the
// slope of the segment (piecewise constant; at a grid node the slope of the segment that starts
// there). A smooth table (k = 1 + 0.2 cos theta) is reproduced to O((2 pi / N)^2) of its
// variation.
//
// References: Kahraman & Singh, "Non-linear dynamics of a spur gear pair", J. Sound Vib. 142
// (1990) 49-75 (the backlash law and its harmonic balance); Kahraman & Singh, "Interactions
// between time-varying mesh stiffness and clearance non-linearities in a geared system", J. Sound
// Vib. 146 (1991) 135-156 (k(theta) with backlash).
#include <limits>
#include <string>
#include <vector>

#include "geardyn/elements/gear_mesh_contact.hpp"
#include "geardyn/hbm/nonlinear_element.hpp"

namespace geardyn::hbm {

/// A periodic function over one mesh cycle: values on the uniform grid theta_i = 2 pi i / N,
/// periodic linear interpolation.
struct MeshCycleTable {
  std::vector<double> values;  ///< N >= 1 values (N = 1: a constant)

  /// The constant `value`.
  static MeshCycleTable constant(double value) { return MeshCycleTable{{value}}; }
  /// The value at phase theta [rad] (any real theta; periodic).
  double value(double theta) const;
  /// d value / d theta at theta: the slope of the segment containing theta (the one starting
  /// there at a grid node); 0 for a constant.
  double slope(double theta) const;
};

/// The parameters of a GearMeshBacklash.
struct GearMeshBacklashParameters {
  MeshCycleTable stiffness;                            ///< k(theta) [N/m], every value > 0
  MeshCycleTable unloaded_te = MeshCycleTable{{0.0}};  ///< e(theta) [m]
  /// Total backlash b [m] along the line of action, >= 0; +infinity: no back-flank contact.
  double backlash = std::numeric_limits<double>::infinity();
  double damping = 0.0;  ///< c [N s/m] >= 0, in contact only
};

/// The mesh law of the header comment.
///
/// loop() reports the regimes over the period as (ElementLoop has stick / slip / open slots):
///   open_fraction  = share of the samples with no contact (inside the backlash),
///   slip_fraction  = share of the samples on the BACK flank (0 without backlash),
///   stick_fraction = NaN (unused);
/// the drive-flank share is 1 - open_fraction - slip_fraction. Single-sided impacts: open > 0,
/// slip = 0; double-sided: slip > 0.
class GearMeshBacklash final : public PointwiseElement {
 public:
  /// Throws InputError (key `<name>.stiffness`, `.unloaded_te`, `.backlash`, `.damping`) for an
  /// empty table, a stiffness value not finite and > 0, a TE value not finite, a backlash NaN or
  /// negative, a damping not finite and >= 0.
  GearMeshBacklash(std::string name, GearMeshBacklashParameters parameters);

  int size() const override { return 1; }
  /// "gear mesh '<name>'".
  std::string describe() const override;
  /// f, df/ddelta, df/ddelta' at (delta, delta', theta, omega). Throws NumericalError for a
  /// non-finite delta or delta'.
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;
  /// True with damping (c > 0).
  bool velocity_dependent() const override { return parameters_.damping > 0.0; }
  /// -c e'(theta) in contact, 0 otherwise.
  void pointwise_omega_derivative(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta,
                                  double omega, Eigen::VectorXd& out) const override;
  /// The AFT loop of PointwiseElement with the regime fractions of the class comment.
  ElementLoop loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                   double omega) const override;

  /// Which flank touches at approach delta and phase theta.
  elements::MeshContactState state(double delta, double theta) const;
  /// The parameters as given.
  const GearMeshBacklashParameters& parameters() const { return parameters_; }
  /// True when the backlash is finite (a back flank exists).
  bool has_backlash() const {
    return parameters_.backlash < std::numeric_limits<double>::infinity();
  }

 private:
  std::string name_;
  GearMeshBacklashParameters parameters_;
};

}  // namespace geardyn::hbm
