#pragma once
// A rolling-element bearing as a nonlinear force element (docs/theory.md §16.5): Z balls or
// rollers at their current angular positions between the inner ring (end j, on the shaft) and
// the outer ring (end i, the housing or ground), each a Hertz contact with load-deflection law
// Q = K_n delta^n (n = 3/2 point contact, 10/9 line contact; A. Palmgren, "Ball and Roller
// Bearing Engineering", 1959; T.A. Harris, "Rolling Bearing Analysis", 4th ed., 2001) that
// carries load only while compressed beyond the clearance. The contacts are summed as vectors
// at the cage position psi_0(t) = psi_00 + omega_c t, so the stiffness varies at the ball-pass
// frequency Z (f_c - f_o) ("varying compliance").
//
// Coordinates (n = 3): radial x, y and axial z of the inner ring relative to the outer ring,
// u = (x, y, z) = (inner) - (outer), in the bearing frame whose z axis is the bearing axis.
// With `spin_angle` a fourth coordinate is the inner ring's rotation angle theta relative to the
// outer ring (the shaft's spin angle, n = 4), and the cage follows it:
// psi_0 = psi_00 + omega_c t + kappa theta with kappa = (1 - gamma) / 2, the cage speed ratio of
// a fixed outer ring (BearingKinematics), so the ball-pass modulation follows the actual shaft
// speed during a run-up (omega_c is then normally 0). The element exerts no torque on theta
// (frictionless rolling), but its force depends on it: the tangent's column 3 is
// d f / d theta = kappa sum_k [Q_k'(delta_k) (e_k' . u) e_k + Q_k e_k'], e_k' = d e_k / d psi. Ring
// tilts (a 5-coordinate bearing with moment stiffness) are not modelled yet: the shaft's tilt at
// the bearing is free, as with a single-row radial bearing seated on one node.
//
// Element k sits at psi_k = psi_0 + 2 pi k / Z (psi measured from x towards y) and its contact
// line has the direction e_k = (cos(alpha) cos(psi_k), cos(alpha) sin(psi_k), sin(alpha)) with
// the contact angle alpha. Its deflection is delta_k = e_k . u - g with the gap
// g = (c_r / 2) cos(alpha) + (c_a / 2) |sin(alpha)|, the projection of the free play on the contact
// line (c_r: diametral clearance, the total radial free travel of the inner ring, Harris's P_d;
// c_a: total axial free travel). A negative clearance is an interference (preload). The element
// pushes the rings apart with Q_k = K_n delta_k^n e_k for delta_k > 0 and nothing otherwise; the
// internal force is f = sum_k Q_k e_k + C v with the constant viscous damping
// C = diag(c_radial, c_radial, c_axial) (a linear dashpot standing for the lubricant film and
// the seat; it acts also across the clearance).
//
// With alpha = 0 (deep-groove ball or cylindrical roller bearing) the elements carry no axial
// load and K_zz = 0: an axial support must come from elsewhere. A single-row angular-contact
// bearing (alpha > 0) carries axial load in +z only (alpha < 0: in -z); a pair is two elements.
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/force_element.hpp"

namespace geardyn::elements {

/// Parameters of a rolling-element bearing. Lengths in m, angles in rad, speeds in rad/s.
struct RollingBearingParams {
  int elements = 0;                 ///< Z, the number of balls or rollers (>= 1)
  double stiffness_constant = 0.0;  ///< K_n, load-deflection constant of one element [N/m^n]
  double exponent = 1.5;            ///< n: 3/2 point contact (ball), 10/9 line contact (roller)
  double radial_clearance = 0.0;    ///< c_r, diametral clearance (total radial play) [m]
  double axial_clearance = 0.0;     ///< c_a, total axial play [m]
  double contact_angle = 0.0;       ///< alpha [rad], |alpha| <= pi/2
  double pitch_diameter = 0.0;      ///< d_m, diameter of the element centres' circle [m]
  double element_diameter = 0.0;    ///< D, ball or roller diameter [m] (< d_m)
  double cage_angle = 0.0;          ///< psi_00, cage position at t = 0 [rad]
  double cage_speed = 0.0;      ///< omega_c [rad/s], set by the caller (BearingKinematics::cage)
  double radial_damping = 0.0;  ///< c_radial [N s/m] on x and y
  double axial_damping = 0.0;   ///< c_axial [N s/m] on z
  /// A fourth coordinate: the inner ring's rotation angle theta relative to the outer ring
  /// [rad], which turns the cage by kappa theta (see above).
  bool spin_angle = false;
  std::string name = "bearing";  ///< for describe()
};

/// Kinematic frequencies of a rolling bearing whose elements roll without slip (T.A. Harris,
/// "Rolling Bearing Analysis", 4th ed. 2001, bearing kinematics). With gamma = D cos(alpha) / d_m
/// and the ring speeds f_i (inner), f_o (outer), in rad/s or Hz (the results are in the same unit):
///   cage (fundamental train)  f_c  = f_i (1 - gamma) / 2 + f_o (1 + gamma) / 2,
///                                    i.e. f_i (1 - D cos(alpha) / d_m) / 2 for a fixed outer ring
///   ball pass, outer ring     BPFO = Z |f_c - f_o|
///   ball pass, inner ring     BPFI = Z |f_i - f_c|
///   element spin (vs cage)    BSF  = (d_m / (2 D)) (1 - gamma^2) |f_i - f_o|
/// A RollingBearing's stiffness varies at Z f_c, the ball-pass frequency BPFO for a fixed outer
/// ring.
struct BearingKinematics {
  int elements = 0;               ///< Z
  double pitch_diameter = 0.0;    ///< d_m [m]
  double element_diameter = 0.0;  ///< D [m]
  double contact_angle = 0.0;     ///< alpha [rad]

  double gamma() const;
  double cage(double inner, double outer = 0.0) const;
  double ball_pass_outer(double inner, double outer = 0.0) const;
  double ball_pass_inner(double inner, double outer = 0.0) const;
  double ball_spin(double inner, double outer = 0.0) const;
};

class RollingBearing final : public ForceElement {
 public:
  /// Checks the parameters; a bad one throws InputError at `where` with the key path
  /// `key_path` + "." + the field's name (e.g. "bearings[2].stiffness_constant").
  RollingBearing(RollingBearingParams params, const std::string& key_path,
                 SourceLocation where = {});

  Eigen::Index size() const override { return p_.spin_angle ? 4 : 3; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                ElementForce& out) const override;
  std::string describe() const override;

  const RollingBearingParams& params() const { return p_; }
  /// The cage angle psi_0(t) = psi_00 + omega_c t [rad] (without the spin angle's part).
  double cage_angle(double t) const { return p_.cage_angle + p_.cage_speed * t; }
  /// The cage angle at u and t: psi_00 + omega_c t (+ kappa theta with spin_angle) [rad].
  double cage_angle(const Eigen::VectorXd& u, double t) const;
  /// kappa = (1 - gamma) / 2: cage turn per inner-ring turn with a fixed outer ring.
  double cage_ratio() const { return kappa_; }
  /// The gap g along each contact line [m] (negative: interference).
  double gap() const { return gap_; }
  /// Deflection delta_k of element k at u and t [m] (negative: not in contact).
  double deflection(const Eigen::VectorXd& u, double t, int k) const;
  /// The kinematic frequencies from Z, d_m, D and alpha.
  BearingKinematics kinematics() const;

 private:
  RollingBearingParams p_;
  double gap_ = 0.0;
  double kappa_ = 0.0;
};

}  // namespace geardyn::elements
