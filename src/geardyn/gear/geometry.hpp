#pragma once
// Geometry of a gear pair as the mesh-excitation chain needs it (docs/theory.md §11.1): radii,
// working pressure angle and centre distance, contact ratios. Cylindrical gears (spur, helical;
// external and internal) follow ISO 21771; bevel and hypoid gears are replaced by their virtual
// cylindrical ("equivalent spur") gears at mid face width, as in ISO 10300-1 and in the
// damper-ring thesis (A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears
// Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 3.2: mid-face
// module from the outer module).
//
// Cylindrical gears (ISO 21771:2007, 4-5):
//   m_t = m_n / cos(beta),  tan(alpha_t) = tan(alpha_n) / cos(beta),
//   sin(beta_b) = sin(beta) cos(alpha_n)
//   r = z m_t / 2,  r_b = r cos(alpha_t),  r_a = r + m_n (h_a* + x),  r_f = r - m_n (h_f* - x)
//   inv(alpha_wt) = inv(alpha_t) + 2 tan(alpha_n) (x1 + x2) / (z1 + z2)
//   a = (z1 + z2) m_t cos(alpha_t) / (2 cos(alpha_wt))
// Internal gears use ISO 21771's signed convention: inside the formulas z2 < 0, so every radius
// of the internal gear is negative and its profile shift x2 > 0 moves its profile towards the
// centre (its tip radius is |r2| - m_n (h_a* + x2), its root radius |r2| + m_n (h_f* - x2)). All
// radii reported here are positive magnitudes. No tip shortening is applied.
//
// Transverse contact ratio (docs/theory.md (11.2), ISO 21771 5.4.2), with p_bt = pi m_t
// cos(alpha_t):
//   external: eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin(alpha_wt)) / p_bt
//   internal: eps_alpha = (sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + a sin(alpha_wt)) / p_bt
//   overlap ratio eps_beta = b sin(beta) / (pi m_n),  total eps_gamma = eps_alpha + eps_beta.
//
// Bevel gears (ISO 23509:2016 / ISO 10300-1:2014 clause 6 and Annex A; Tredgold approximation):
//   pitch cone angles  tan(delta1) = sin(Sigma) / (z2/z1 + cos(Sigma)),  delta2 = Sigma - delta1
//   outer cone distance R_e = m_e z1 / (2 sin(delta1)), mean cone distance R_m = R_e - b/2,
//   mid-face (mean transverse) module m_m = m_e (R_e - b/2) / R_e, mean radius r_m = m_m z / 2,
//   mean normal module m_mn = m_m cos(beta_m).
//   Virtual cylindrical gear: r_v = r_m / cos(delta), z_v = z / cos(delta) (Tredgold),
//   helix angle beta_m, transverse module m_m, r_va = r_v + m_mn (h_a* + x),
//   r_vf = r_v - m_mn (h_f* - x), centre distance a_v = r_v1 + r_v2 (bevel gears use balanced
//   profile shift x1 = -x2, checked).
// Hypoid gears (approximation, stated): the pitch cones are taken from the tooth counts and the
// shaft angle as for a bevel pair (the offset is neglected there); the wheel is described by its
// outer module and mean spiral angle beta_2, the pinion by its own mean spiral angle beta_1 and
// the same mean normal module, so r_m1 = r_m2 (z1/z2) cos(beta_2) / cos(beta_1) (pinion
// enlargement). The virtual pair uses the mean spiral angle (beta_1 + beta_2) / 2.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {

enum class GearType { Spur, Helical, StraightBevel, SpiralBevel, Hypoid };
enum class MeshType { External, Internal };

std::string_view to_string(GearType type);
std::string_view to_string(MeshType type);
/// "spur", "helical", "straight_bevel", "spiral_bevel", "hypoid"; anything else throws
/// InputError at `key_path` listing the accepted names.
GearType parse_gear_type(std::string_view text, const std::string& key_path,
                         const SourceLocation& where = {});
/// "external", "internal".
MeshType parse_mesh_type(std::string_view text, const std::string& key_path,
                         const SourceLocation& where = {});

/// True for straight bevel, spiral bevel and hypoid gears.
bool is_bevel(GearType type);

/// Input of one gear pair. Gear 1 is the pinion, gear 2 the wheel (for an internal mesh: the
/// internal gear). All lengths in metres, angles in radians.
struct GearPairSpec {
  std::string name = "gear_pair";      ///< label in tables
  std::string key_path = "gear_pair";  ///< key path used in error messages
  SourceLocation where;                ///< where the pair was read from (for error messages)

  GearType type = GearType::Spur;
  MeshType mesh = MeshType::External;  ///< internal only for spur and helical gears
  int teeth_pinion = 0;                ///< z1 > 0
  int teeth_wheel = 0;                 ///< z2 > 0 (internal gear: its tooth count, positive)
  /// Optional z2/z1 (NaN: not checked). If given it must equal z2/z1 within `ratio_tolerance`
  /// (relative), else InputError.
  double ratio = std::numeric_limits<double>::quiet_NaN();
  double ratio_tolerance = 1e-6;

  /// Cylindrical gears: normal module m_n. Bevel gears: outer transverse module m_e (at the
  /// heel); hypoid: the wheel's outer transverse module. [m]
  double module_m = std::numeric_limits<double>::quiet_NaN();
  double pressure_angle_rad = units::kPi / 9.0;  ///< normal pressure angle alpha_n of the rack
  /// Helical: reference helix angle beta. Spiral bevel: mean spiral angle beta_m. Hypoid: the
  /// wheel's mean spiral angle. Must be 0 for spur and straight bevel gears.
  double helix_angle_rad = 0.0;
  /// Hypoid only: the pinion's mean spiral angle beta_1 (> wheel's). NaN elsewhere.
  double pinion_spiral_angle_rad = std::numeric_limits<double>::quiet_NaN();
  double face_width_m = std::numeric_limits<double>::quiet_NaN();  ///< b > 0
  double addendum_coefficient = 1.0;   ///< h_aP* = h_aP / m_n of the basic rack
  double dedendum_coefficient = 1.25;  ///< h_fP* = h_fP / m_n of the basic rack
  double profile_shift_pinion = 0.0;   ///< x1
  double profile_shift_wheel = 0.0;    ///< x2 (ISO 21771 sign convention, see above)
  /// Cylindrical gears: working centre distance a (NaN: the zero-backlash value for x1 + x2).
  /// If given, it must leave non-negative backlash for the profile shifts.
  double centre_distance_m = std::numeric_limits<double>::quiet_NaN();
  double shaft_angle_rad = 0.5 * units::kPi;  ///< bevel / hypoid: Sigma in (0, pi)
  /// Bevel / hypoid: outer cone distance R_e (NaN: from m_e, z1 and delta1). If given it must
  /// agree with m_e z1 / (2 sin delta1) to 1e-6 relative.
  double outer_cone_distance_m = std::numeric_limits<double>::quiet_NaN();
};

/// One member of the pair. For bevel / hypoid gears the radii are those of the virtual
/// cylindrical gear at mid face; `mean_pitch_radius_m` is the real mean pitch radius.
struct GearGeometry {
  int teeth = 0;               ///< z
  double virtual_teeth = 0.0;  ///< z_v = z / cos(delta) (Tredgold); = z for cylindrical gears
  /// ISO 6336-1 virtual number of teeth of the normal section, z_n = z_v / (cos^2(beta_b)
  /// cos(beta)); infinite for an internal gear (ISO 6336-1 Method B sets z_n2 = infinity there).
  double normal_virtual_teeth = 0.0;
  double pitch_radius_m = 0.0;          ///< reference radius r (virtual r_v for bevel)
  double base_radius_m = 0.0;           ///< r_b (virtual for bevel)
  double tip_radius_m = 0.0;            ///< r_a (virtual for bevel)
  double root_radius_m = 0.0;           ///< r_f (virtual for bevel)
  double working_pitch_radius_m = 0.0;  ///< r_w = r_b / cos(alpha_wt)
  double mean_pitch_radius_m = 0.0;     ///< real radius for F_t = T / r (= r for cylindrical)
  double pitch_cone_angle_rad = 0.0;    ///< delta (0 for cylindrical gears)
  double spiral_angle_rad = 0.0;        ///< helix / mean spiral angle of this member
  double profile_shift = 0.0;           ///< x
};

struct GearPairGeometry {
  GearPairSpec spec;  ///< the input, as given
  GearGeometry pinion, wheel;
  double ratio = 0.0;                          ///< z2 / z1
  double normal_module_m = 0.0;                ///< m_n (bevel: mean normal module m_mn)
  double transverse_module_m = 0.0;            ///< m_t (bevel: mid-face module m_m)
  double normal_pressure_angle_rad = 0.0;      ///< alpha_n
  double transverse_pressure_angle_rad = 0.0;  ///< alpha_t
  double working_pressure_angle_rad = 0.0;     ///< alpha_wt (transverse)
  double helix_angle_rad = 0.0;                ///< beta (virtual pair's for bevel / hypoid)
  double base_helix_angle_rad = 0.0;           ///< beta_b
  double centre_distance_m = 0.0;              ///< working a (virtual a_v for bevel / hypoid)
  double face_width_m = 0.0;                   ///< b
  double transverse_base_pitch_m = 0.0;        ///< p_bt = pi m_t cos(alpha_t)
  double path_of_contact_m = 0.0;              ///< length of the path of contact g_alpha
  double transverse_contact_ratio = 0.0;       ///< eps_alpha
  double overlap_ratio = 0.0;                  ///< eps_beta
  double total_contact_ratio = 0.0;            ///< eps_gamma
  // Bevel / hypoid only (NaN otherwise):
  double outer_module_m = std::numeric_limits<double>::quiet_NaN();         ///< m_e
  double mean_module_m = std::numeric_limits<double>::quiet_NaN();          ///< m_m (mid face)
  double outer_cone_distance_m = std::numeric_limits<double>::quiet_NaN();  ///< R_e
  double mean_cone_distance_m = std::numeric_limits<double>::quiet_NaN();   ///< R_m
};

/// Validates `spec` and computes the geometry. Throws InputError (key path
/// `spec.key_path + ".<field>"`) for: non-positive tooth counts, module or face width; a ratio
/// that disagrees with z2/z1; a helix / spiral angle that does not fit the gear type; an internal
/// bevel gear; an internal gear with z2 <= z1; a centre distance that leaves negative backlash; a
/// tip circle at or below the base circle; involute interference (a tip reaching past the
/// mating gear's interference point); and a transverse contact ratio below 1.
GearPairGeometry gear_pair_geometry(const GearPairSpec& spec);

/// One row per member of each pair: pair, member, teeth, virtual_teeth, pitch_radius_m,
/// mean_pitch_radius_m, base_radius_m, tip_radius_m, root_radius_m, working_pitch_radius_m,
/// pitch_cone_angle_deg, spiral_angle_deg, profile_shift, and the pair's centre_distance_m,
/// normal_module_m, transverse_module_m, working_pressure_angle_deg, transverse_contact_ratio,
/// overlap_ratio, total_contact_ratio.
Table geometry_table(const std::vector<GearPairGeometry>& pairs);

/// inv(alpha) = tan(alpha) - alpha, and its inverse by Newton's method (0 <= inv < ~1.5).
double involute(double alpha_rad);
double inverse_involute(double inv_value);

}  // namespace geardyn::gear
