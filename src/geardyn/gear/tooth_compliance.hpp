#pragma once
// Analytic compliance of a meshing tooth pair at one point of the transverse path of contact,
// per unit face width: the "slice" compliance of the loaded tooth contact analysis
// (gear/tooth_contact.hpp, docs/theory.md §15).
//
// Each tooth is a non-uniform cantilever on the gear body: bending, shear and axial compression
// of the tooth by the potential-energy method on the real involute profile and root, and the
// fillet-foundation (gear body) deflection; the flanks add the Hertzian approach of two
// cylinders in line contact, nonlinear in the load. Sources and formulas are given in the .cpp
// and in docs/theory.md §15.
//
// Conventions:
//   * s is the position along the transverse path of contact, from its start A (s = 0, where a
//     tooth pair enters contact: the pinion's root meets the wheel's tip when the pinion drives)
//     to its end E (s = g_alpha = GearPairGeometry::path_of_contact_m). This is the convention of
//     gear/mesh_stiffness.hpp.
//   * a "line load" w is the force per unit face width along the transverse line of action
//     [N/m]; a compliance is the deflection along the line of action per line load [m / (N/m)]
//     = [m^2/N]. Stiffness per unit face width = 1 / compliance [N/m^2].
//   * cylindrical gears (spur, helical; external and internal) in the transverse section; a
//     helical gear is sliced into thin transverse spur gears (the thin-slice model).
#include <limits>

#include "geardyn/gear/geometry.hpp"

namespace geardyn::gear {

struct ElasticConstants {
  double youngs_modulus_pa = 206e9;  ///< E > 0
  double poisson_ratio = 0.3;        ///< nu in (-1, 0.5)
};

struct ToothComplianceOptions {
  ElasticConstants pinion, wheel;
  /// Fillet (gear body) deflection of both teeth (false: tooth cantilever only).
  bool foundation = true;
  /// Root fillet radius of the basic rack rho_fP / m_n (ISO 53 profile A: 0.38). It sets the
  /// tooth thickness at the root circle S_f of Sainsot's foundation formula (the end of the
  /// rack-tip flat); must leave a flat >= 0 on the rack tip.
  double root_fillet_coefficient = 0.38;
  /// Bore radius r_int of the gear body in Sainsot's formula [m] (NaN: r_f / 2). Sainsot's fit
  /// covers 1.4 <= r_f / r_int <= 7: a larger bore is refused (InputError), a smaller one is
  /// taken as r_f / 7 (the body deflection no longer depends on the bore there). For an
  /// internal gear `bore_radius_wheel_m` is the outer radius of its rim r_o (NaN: 1.5 r_f), and
  /// the ring is given the external body of the same rim thickness (see the .cpp).
  double bore_radius_pinion_m = std::numeric_limits<double>::quiet_NaN();
  double bore_radius_wheel_m = std::numeric_limits<double>::quiet_NaN();
  /// Tooth bending and compression in plane strain, E / (1 - nu^2) (a slice of a wide tooth);
  /// false: plane stress, E (what most potential-energy papers use).
  bool plane_strain = true;
};

/// Compliances of the two teeth at one path position [m^2/N] (see conventions above).
struct PointCompliance {
  double bending_pinion = 0.0, shear_pinion = 0.0, compression_pinion = 0.0;
  double foundation_pinion = 0.0;
  double bending_wheel = 0.0, shear_wheel = 0.0, compression_wheel = 0.0;
  double foundation_wheel = 0.0;
  /// Sum of every term above: the linear (body) compliance of the pair at this point.
  double body() const {
    return bending_pinion + shear_pinion + compression_pinion + foundation_pinion + bending_wheel +
           shear_wheel + compression_wheel + foundation_wheel;
  }
};

/// Tooth-pair compliance along the path of contact of one cylindrical gear pair. Immutable and
/// thread-safe after construction (precomputes what it needs).
class ToothCompliance {
 public:
  /// Throws InputError (key path geometry.spec.key_path + ".<field>") for a bevel / hypoid pair
  /// (".type"), non-positive moduli (".youngs_modulus_pinion" / "_wheel"), a Poisson ratio
  /// outside (-1, 0.5) (".poisson_ratio_*"), a rack fillet that leaves no rack-tip flat
  /// (".root_fillet_coefficient"), a pointed tooth (".profile_shift_*") and a bore outside
  /// (0, r_f) or outside Sainsot's body range (".bore_radius_*").
  ToothCompliance(const GearPairGeometry& geometry, const ToothComplianceOptions& options = {});

  /// Body compliance terms at path position s in [0, g_alpha] (clamped to it).
  PointCompliance at(double s) const;

  /// Hertzian approach of the two flanks [m] along the transverse line of action under the line
  /// load w >= 0 [N/m] at s (C. Weber, K. Banaschek 1955): the approach of the two tooth centre
  /// lines through the contact zone, w [A(s) - k ln w] with k = sum (1 - nu_i^2) / (pi E_i)
  /// (divided by cos(beta_b) for helical gears); 0 for w = 0. Valid while the Hertz half width
  /// stays well below the tooth half thickness (b_H < ~h_c; at 300 N/mm on m = 3 mm teeth
  /// b_H / h_c ~ 0.06): beyond that the log term and this derivative lose their meaning.
  double hertz_approach(double s, double w) const;
  /// d(hertz_approach)/dw at (s, w) [m^2/N], analytic: hertz_approach / w - k (/ cos beta_b);
  /// finite and positive for w > 0 in the range above; +infinity for w <= 0.
  double hertz_compliance(double s, double w) const;
  /// Hertz half-width b_H [m] and peak pressure p_H [Pa] of the line contact (K.L. Johnson,
  /// "Contact Mechanics", 1985, sec. 4.3) under the line load w [N/m] (per unit face width
  /// along the transverse line of action; helical gears: the normal section's load per unit
  /// length of contact line and its normal radii of curvature are used).
  double hertz_half_width(double s, double w) const;
  double hertz_max_pressure(double s, double w) const;

  /// Radii of the contact point on the pinion and the wheel at s [m], and the relative radius
  /// of curvature of the flanks 1/rho = 1/rho1 +- 1/rho2 (+ external, - internal) [m].
  double pinion_radius(double s) const;
  double wheel_radius(double s) const;
  double relative_curvature_radius(double s) const;

  const GearPairGeometry& geometry() const { return geometry_; }

 private:
  /// One member's tooth as the integrals need it (transverse section, magnitudes).
  struct Tooth {
    bool internal = false;
    double rb = 0.0, ra = 0.0, rf = 0.0;
    /// Half tooth angle beta(alpha) = c0 - inv(alpha) (external), c0 + inv(alpha) (internal).
    double c0 = 0.0;
    double alpha_root = 0.0;  ///< pressure angle where the involute part of the cantilever ends
    double y_root = 0.0;      ///< centre-line coordinate of the cantilever's root
    double y_base = 0.0;      ///< external, r_f < r_b: end of the straight part (base circle)
    double h_base = 0.0;      ///< its half thickness (0: no straight part)
    double e_beam = 0.0, g_shear = 0.0, e_body = 0.0;  ///< E' (plane strain or E), G, E
    double hertz_k = 0.0;                              ///< (1 - nu^2) / (pi E)
    double nu = 0.0;
    double root_thickness = 0.0;                                    ///< S_f [m]
    double l_star = 0.0, m_star = 0.0, p_star = 0.0, q_star = 0.0;  ///< Sainsot's L*, M*, P*, Q*
  };
  /// Contact point on one tooth: pressure angle of the profile there, radius, centre-line
  /// coordinate y_c and half thickness h_c, load angle alpha_1 to the normal of the centre line.
  struct ContactPoint {
    double alpha = 0.0, r = 0.0, y = 0.0, h = 0.0, load_angle = 0.0;
  };
  ContactPoint contact_point(const Tooth& tooth, double roll_length) const;
  void tooth_terms(const Tooth& tooth, double roll_length, double& bending, double& shear,
                   double& compression, double& foundation) const;
  /// Distances of the contact point from the base-circle tangent points T1, T2 (the
  /// transverse radii of curvature of the flanks) [m].
  double roll_pinion(double s) const;
  double roll_wheel(double s) const;
  double clamp_s(double s) const;

  GearPairGeometry geometry_;
  ToothComplianceOptions options_;
  Tooth pinion_, wheel_;
  double e_star_ = 0.0;  ///< 1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2
  double cos_beta_b_ = 1.0;
};

}  // namespace geardyn::gear
