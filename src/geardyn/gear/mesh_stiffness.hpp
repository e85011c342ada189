#pragma once
// Gear mesh stiffness from geometry: ISO 6336-1:2019 Method B (clause 9, "Tooth stiffness
// parameters c' and c_gamma"; 9.3) and a time-varying mesh stiffness over one mesh cycle built on
// it, with the synthetic static transmission error e = F_s / k that the dynamic mesh model
// (docs/theory.md §13) takes as input.
//
// ISO 6336-1:2019 9.3 (Method B), steel gear pairs, values per unit face width:
//   q' = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1^2 + C9 x2^2
//        [mm·µm/N],  C1..C9 = 0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193,
//        -0.24188, 0.00529, 0.00182;  z_n = z / (cos^2(beta_b) cos(beta)) (z_n2 = inf, internal)
//   c'_th = 1 / q'                                   theoretical single stiffness
//   c' = c'_th C_M C_R C_B cos(beta) (E / E_st) f_load      single stiffness [N/(mm·µm)]
//     C_M = 0.8 (measured vs theoretical), C_R = 1 + ln(b_s/b) / (5 exp(s_R / (5 m_n))) for
//     gear blanks with a web (1 for solid discs), C_B = [1 + 0.5 (1.2 - h_fP/m_n)]
//     [1 - 0.02 (20 deg - alpha_Pn)] (basic rack; the pair uses the mean of both members),
//     E = 2 E1 E2 / (E1 + E2), E_st = 206 000 N/mm^2,
//     f_load = (F_t K_A / b / (100 N/mm))^0.25 when F_t K_A / b < 100 N/mm, else 1.
//   c_gamma_alpha = c' (0.75 eps_alpha + 0.25),  c_gamma_beta = 0.85 c_gamma_alpha
//   SI: 1 N/(mm·µm) = 1e9 N/m^2 (per metre of face width); k = c b.
// For bevel and hypoid gears the virtual cylindrical pair of geometry.hpp is used (as
// ISO 10300-1 does for its virtual gears); this is an approximation outside ISO 6336's scope.
//
// Time-varying mesh stiffness (model: ISO single-pair stiffness with load sharing over the
// contact ratio, NOT a potential-energy model). Along the transverse path of contact
// s in [0, g_alpha], g_alpha = eps_alpha p_bt, one tooth pair has the stiffness per unit face width
//     k_pair(s) = c' (0.75 + 0.25 s / L)             0 <= s < L        (entering, double zone)
//               = c'                                  L <= s <= g - L   (single contact zone)
//               = c' (0.75 + 0.25 (g - s) / L)        g - L < s <= g    (leaving, double zone)
// with L = (eps_alpha - 1) p_bt the length of each double-contact zone. This is the single-pair
// law for which the mean over a mesh cycle equals ISO's c_gamma_alpha = c'(0.75 eps_alpha + 0.25)
// exactly (1 <= eps_alpha <= 2): the pair is stiffest (c') in single contact and its stiffness
// falls to 0.75 c' at the start and end of the path, so that two pairs in the double zone give
// 1.75 c'. For eps_alpha > 2 the ramps are limited to L = g/2 and the mean no longer follows ISO's
// formula (ISO gives it for ordinary contact ratios).
// Spur gears: k(u) = b sum_j k_pair((u + j) p_bt). Helical gears: the contact lines are inclined
// by the base helix angle in the plane of action, so a pair whose leading face end is at path
// position s0 contributes the integral over the face width
//     int_0^b k_pair(s0 - y tan(beta_b)) dy,
// evaluated in closed form from the piecewise-quadratic primitive of k_pair.
// The mesh cycle coordinate u in [0, 1) is the pinion rotation over one base pitch; u = 0 is the
// instant a new tooth pair enters contact (at the start of the path, leading face end), the
// convention the tooth-load window and the STE input share (docs/theory.md §12.1).
#include <limits>
#include <vector>

#include "geardyn/gear/geometry.hpp"

namespace geardyn::gear {

struct IsoStiffnessOptions {
  double correction_factor = 0.8;  ///< C_M (ISO 6336-1: 0.8 for solid disc gears)
  /// Gear blank with a web: rim thickness s_R and web thickness b_s [m]. NaN (both): solid disc,
  /// C_R = 1. ISO's range 0.2 <= b_s/b <= 1.2 and s_R/m_n >= 1 is enforced (InputError outside).
  double rim_thickness_m = std::numeric_limits<double>::quiet_NaN();
  double web_thickness_m = std::numeric_limits<double>::quiet_NaN();
  /// Nominal tangential force F_t [N] for ISO's load correction. NaN: no correction (the line
  /// load F_t K_A / b is taken to be >= 100 N/mm, where ISO's values apply unchanged).
  double tangential_force_n = std::numeric_limits<double>::quiet_NaN();
  double application_factor = 1.0;          ///< K_A
  double youngs_modulus_pinion_pa = 206e9;  ///< E1
  double youngs_modulus_wheel_pa = 206e9;   ///< E2
};

/// ISO 6336-1 Method B tooth stiffness of a pair. Per-unit-width values in N/(mm·µm) (ISO's
/// unit), totals in SI.
struct IsoStiffness {
  double normal_virtual_teeth_pinion = 0.0;   ///< z_n1
  double normal_virtual_teeth_wheel = 0.0;    ///< z_n2 (inf for an internal gear)
  double flexibility_q_prime = 0.0;           ///< q' [mm·µm/N]
  double theoretical_single_stiffness = 0.0;  ///< c'_th [N/(mm·µm)]
  double correction_factor = 0.0;             ///< C_M
  double blank_factor = 0.0;                  ///< C_R
  double basic_rack_factor = 0.0;             ///< C_B
  double helix_factor = 0.0;                  ///< cos(beta)
  double material_factor = 0.0;               ///< E / E_st
  double load_factor = 1.0;                   ///< f_load (1: no correction)
  double single_stiffness = 0.0;              ///< c' [N/(mm·µm)]
  double mesh_stiffness_alpha = 0.0;          ///< c_gamma_alpha [N/(mm·µm)]
  double mesh_stiffness_beta = 0.0;           ///< c_gamma_beta [N/(mm·µm)]
  double single_stiffness_n_per_m = 0.0;      ///< c' b [N/m]
  double mesh_stiffness_n_per_m = 0.0;        ///< c_gamma_alpha b [N/m]
};

/// ISO 6336-1:2019 Method B single and mesh stiffness. Throws InputError for options out of
/// range (non-positive moduli or factors, a blank outside ISO's range, F_t <= 0).
IsoStiffness iso_mesh_stiffness(const GearPairGeometry& geometry,
                                const IsoStiffnessOptions& options = {});

struct MeshStiffnessOptions {
  int samples = 512;  ///< samples over one mesh cycle (>= 16)
  IsoStiffnessOptions iso;
};

/// Mesh stiffness along the transverse line of action over one mesh cycle, uniform samples
/// u_j = j / n, j = 0 .. n-1 (sample 0: a tooth pair enters contact).
struct MeshStiffnessCurve {
  std::vector<double> mesh_fraction;      ///< u_j in [0, 1)
  std::vector<double> pinion_angle_rad;   ///< u_j 2 pi / z1
  std::vector<double> stiffness_n_per_m;  ///< k(u_j)
  /// Pairs in contact weighted by the share of the face width in contact (integer for spur).
  std::vector<double> pairs_in_contact;
  double mean_stiffness_n_per_m = 0.0;  ///< mean of the samples
  double min_stiffness_n_per_m = 0.0;
  double max_stiffness_n_per_m = 0.0;
  double mesh_period_rad = 0.0;       ///< 2 pi / z1 (pinion rotation per mesh cycle)
  double double_zone_length_m = 0.0;  ///< L: length of each ramp of k_pair along the path
  IsoStiffness iso;                   ///< the ISO values the curve is built on
};

/// Time-varying mesh stiffness (model in the header comment). Throws InputError for fewer than
/// 16 samples and for the ISO options as iso_mesh_stiffness does.
MeshStiffnessCurve time_varying_mesh_stiffness(const GearPairGeometry& geometry,
                                               const MeshStiffnessOptions& options = {});

/// Synthetic static transmission error from a stiffness curve (docs/theory.md (11.5), inverted):
///   F_s = T1 / r_b1,  e(u) = F_s / k(u) [m along the line of action],  angular e / r_b1 [rad].
/// r_b1 is the pinion base radius (bevel: r_m1 cos(alpha_t), the real mean radius projected on
/// the line of action of the virtual gear). Sample 0 is the tooth entering contact.
struct SyntheticSte {
  std::vector<double> pinion_angle_rad;
  std::vector<double> ste_m;    ///< e(u) [m]
  std::vector<double> ste_rad;  ///< e(u) / r_b1 [rad], pinion rotation
  double static_force_n = 0.0;  ///< F_s
  double base_radius_m = 0.0;   ///< r_b1 used for F_s and the angular STE
  double mean_ste_m = 0.0;
};

/// Throws InputError for a non-positive or non-finite torque.
SyntheticSte synthetic_ste(const MeshStiffnessCurve& curve, const GearPairGeometry& geometry,
                           double pinion_torque_nm);

/// Table "mesh_stiffness": mesh_fraction, pinion_angle_rad, stiffness_n_per_m, pairs_in_contact,
/// and, if `ste` is given, ste_m and ste_rad.
Table mesh_stiffness_table(const MeshStiffnessCurve& curve, const SyntheticSte* ste = nullptr);

}  // namespace geardyn::gear
