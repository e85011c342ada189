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
  /// Root fillet radius of the basic rack rho_fP / m_n (ISO 53 profile A: 0.38).
  double root_fillet_coefficient = 0.38;
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
  /// Throws InputError (key path geometry.spec.key_path + ".<field>") for a bevel / hypoid pair,
  /// non-positive moduli or a Poisson ratio outside (-1, 0.5).
  ToothCompliance(const GearPairGeometry& geometry, const ToothComplianceOptions& options = {});

  /// Body compliance terms at path position s in [0, g_alpha] (clamped to it).
  PointCompliance at(double s) const;

  /// Hertzian approach of the two flanks [m] under the line load w >= 0 [N/m] at s: nonlinear
  /// (w ln(1/w)-like for line contact); 0 for w = 0.
  double hertz_approach(double s, double w) const;
  /// d(hertz_approach)/dw at (s, w) [m^2/N]; finite for w > 0.
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
  GearPairGeometry geometry_;
  ToothComplianceOptions options_;
  // implementation data (tabulated profiles, cached integrals) as needed
};

}  // namespace geardyn::gear
