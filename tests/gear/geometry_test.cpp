// Gear pair geometry: radii, working pressure angle, contact ratios, bevel virtual gears, input
// validation.
#include "geardyn/gear/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

using namespace geardyn::gear;
constexpr double kDeg = std::numbers::pi / 180.0;

GearPairSpec spur(int z1, int z2, double m) {
  GearPairSpec s;
  s.name = "spur";
  s.type = GearType::Spur;
  s.teeth_pinion = z1;
  s.teeth_wheel = z2;
  s.module_m = m;
  s.face_width_m = 20e-3;
  return s;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Reference: the contact-ratio figures of the [mesh-excitation] issue, docs/theory.md (11.2)
// formula
//   eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin(alpha_w)) / (pi m cos alpha).
//    pinion (z1) --- a --- wheel (z2), standard addendum 1 m, standard centre distance.
// 62/62, m = 2 mm, alpha = 20 deg: ra = 64 mm, rb = 62 cos 20 mm, a = 124 mm -> 1.7897798668.
// The figure is given to 11 digits; 1e-9 relative is well above double rounding (~1e-15).
TEST(GearGeometry, SpurContactRatio62x62MatchesReference) {
  const GearPairGeometry g = gear_pair_geometry(spur(62, 62, 2e-3));
  EXPECT_LT(rel(g.transverse_contact_ratio, 1.7897798668), 1e-9);
  EXPECT_DOUBLE_EQ(g.overlap_ratio, 0.0);
  EXPECT_DOUBLE_EQ(g.total_contact_ratio, g.transverse_contact_ratio);
}

// 20/40, m = 3 mm: ra1 = 33, ra2 = 63, a = 90 mm -> eps_alpha = 1.6351859636.
TEST(GearGeometry, SpurContactRatio20x40MatchesReference) {
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40, 3e-3));
  EXPECT_LT(rel(g.transverse_contact_ratio, 1.6351859636), 1e-9);
}

// Standard spur radii follow from the definitions r = z m / 2, r_b = r cos(alpha),
// r_a = r + m, r_f = r - 1.25 m, a = r1 + r2; working pressure angle = alpha for x1 + x2 = 0.
TEST(GearGeometry, SpurRadiiAndCentreDistance) {
  const GearPairGeometry g = gear_pair_geometry(spur(20, 40, 3e-3));
  EXPECT_NEAR(g.pinion.pitch_radius_m, 30e-3, 1e-15);
  EXPECT_NEAR(g.wheel.pitch_radius_m, 60e-3, 1e-15);
  EXPECT_NEAR(g.pinion.base_radius_m, 30e-3 * std::cos(20 * kDeg), 1e-15);
  EXPECT_NEAR(g.pinion.tip_radius_m, 33e-3, 1e-15);
  EXPECT_NEAR(g.wheel.root_radius_m, 56.25e-3, 1e-15);
  EXPECT_NEAR(g.centre_distance_m, 90e-3, 1e-15);
  EXPECT_NEAR(g.working_pressure_angle_rad, 20 * kDeg, 1e-12);
  EXPECT_NEAR(g.pinion.working_pitch_radius_m, 30e-3, 1e-15);
  EXPECT_DOUBLE_EQ(g.ratio, 2.0);
}

// Profile-shifted pair at the zero-backlash centre distance. Oracle: the defining condition of
// backlash-free meshing (ISO 21771 5.2): on the working pitch circles the tooth thicknesses add up
// to the working circular pitch,
//   s_w1 + s_w2 = 2 pi r_w1 / z1,  s_w = 2 r_w (s / (2 r) + inv(alpha_t) - inv(alpha_wt)),
//   s = m (pi/2 + 2 x tan(alpha)).
// The residual is rounding only (Newton solves inv() to 1e-15); tolerance 1e-12 relative.
TEST(GearGeometry, ProfileShiftGivesBacklashFreeWorkingCircles) {
  GearPairSpec s = spur(17, 35, 4e-3);
  s.profile_shift_pinion = 0.4;
  s.profile_shift_wheel = 0.15;
  const GearPairGeometry g = gear_pair_geometry(s);
  const double alpha = 20 * kDeg, m = 4e-3;
  auto sw = [&](const GearGeometry& gg, double x) {
    const double thickness = m * (std::numbers::pi / 2 + 2 * x * std::tan(alpha));
    return 2 * gg.working_pitch_radius_m *
           (thickness / (2 * gg.pitch_radius_m) + involute(alpha) -
            involute(g.working_pressure_angle_rad));
  };
  const double pitch_w = 2 * std::numbers::pi * g.pinion.working_pitch_radius_m / 17;
  EXPECT_LT(rel(sw(g.pinion, 0.4) + sw(g.wheel, 0.15), pitch_w), 1e-12);
  EXPECT_GT(g.centre_distance_m, 0.5 * m * (17 + 35));
  // Same pair with that centre distance given explicitly: same working pressure angle.
  s.centre_distance_m = g.centre_distance_m;
  const GearPairGeometry g2 = gear_pair_geometry(s);
  EXPECT_NEAR(g2.working_pressure_angle_rad, g.working_pressure_angle_rad, 1e-12);
  // A centre distance 0.1 mm smaller would make the teeth overlap.
  s.centre_distance_m = g.centre_distance_m - 1e-4;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
}

TEST(GearGeometry, InverseInvoluteRoundTrips) {
  for (double a : {0.05, 0.2, 0.35, 0.6, 1.0}) EXPECT_NEAR(inverse_involute(involute(a)), a, 1e-14);
}

// Helical pair: m_n = 3 mm, beta = 15 deg, b = 30 mm. ISO 21771 definitions:
//   m_t = m_n / cos(beta), tan(alpha_t) = tan(alpha_n) / cos(beta),
//   eps_beta = b sin(beta) / (pi m_n); contact ratio uses p_bt = pi m_t cos(alpha_t).
TEST(GearGeometry, HelicalTransverseQuantitiesAndOverlapRatio) {
  GearPairSpec s = spur(20, 40, 3e-3);
  s.type = GearType::Helical;
  s.helix_angle_rad = 15 * kDeg;
  s.face_width_m = 30e-3;
  const GearPairGeometry g = gear_pair_geometry(s);
  const double mt = 3e-3 / std::cos(15 * kDeg);
  const double at = std::atan(std::tan(20 * kDeg) / std::cos(15 * kDeg));
  EXPECT_NEAR(g.transverse_module_m, mt, 1e-15);
  EXPECT_NEAR(g.transverse_pressure_angle_rad, at, 1e-14);
  EXPECT_NEAR(g.pinion.pitch_radius_m, 10 * mt, 1e-15);
  EXPECT_NEAR(g.overlap_ratio, 30e-3 * std::sin(15 * kDeg) / (std::numbers::pi * 3e-3), 1e-13);
  const double ra1 = 10 * mt + 3e-3, ra2 = 20 * mt + 3e-3;
  const double rb1 = 10 * mt * std::cos(at), rb2 = 20 * mt * std::cos(at);
  const double eps = (std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
                      30 * mt * std::sin(at)) /
                     (std::numbers::pi * mt * std::cos(at));
  EXPECT_LT(rel(g.transverse_contact_ratio, eps), 1e-12);
  EXPECT_NEAR(g.total_contact_ratio, g.transverse_contact_ratio + g.overlap_ratio, 1e-14);
  // Base helix angle: sin(beta_b) = sin(beta) cos(alpha_n) (ISO 21771), equivalently
  // tan(beta_b) = tan(beta) cos(alpha_t).
  EXPECT_NEAR(std::tan(g.base_helix_angle_rad), std::tan(15 * kDeg) * std::cos(at), 1e-14);
}

// Internal spur mesh 20/100, m = 2 mm: ring tip radius 100 - 2 = 98 mm (teeth point inwards),
// root radius 102.5 mm, a = 80 mm, and the internal formula
//   eps_alpha = (sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + a sin(alpha)) / (pi m cos(alpha)).
// The internal mesh has a larger contact ratio than the same pinion on an external 100-tooth
// gear (the concave ring flank wraps the pinion).
TEST(GearGeometry, InternalSpurMesh) {
  GearPairSpec s = spur(20, 100, 2e-3);
  s.mesh = MeshType::Internal;
  const GearPairGeometry g = gear_pair_geometry(s);
  EXPECT_NEAR(g.wheel.tip_radius_m, 98e-3, 1e-15);
  EXPECT_NEAR(g.wheel.root_radius_m, 102.5e-3, 1e-15);
  EXPECT_NEAR(g.centre_distance_m, 80e-3, 1e-15);
  const double c = std::cos(20 * kDeg);
  const double rb1 = 20e-3 * c, rb2 = 100e-3 * c;
  const double eps = (std::sqrt(22e-3 * 22e-3 - rb1 * rb1) - std::sqrt(98e-3 * 98e-3 - rb2 * rb2) +
                      80e-3 * std::sin(20 * kDeg)) /
                     (std::numbers::pi * 2e-3 * c);
  EXPECT_LT(rel(g.transverse_contact_ratio, eps), 1e-12);
  const GearPairGeometry ext = gear_pair_geometry(spur(20, 100, 2e-3));
  EXPECT_GT(g.transverse_contact_ratio, ext.transverse_contact_ratio);
  EXPECT_TRUE(std::isinf(g.wheel.normal_virtual_teeth));
}

// Involute interference of an internal mesh: the ring's tip circle must enclose the pinion's
// interference point T1, r_a2^2 >= r_b2^2 + (a sin(alpha))^2. For 20/60 teeth, m = 2 mm,
// standard addendum: r_a2 = 58 mm < sqrt(56.382^2 + 13.681^2) = 58.018 mm -> refused.
TEST(GearGeometry, InternalMeshInterferenceIsAnInputError) {
  GearPairSpec s = spur(20, 60, 2e-3);
  s.mesh = MeshType::Internal;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
}

// Bevel pair z = 20/40, Sigma = 90 deg, outer module 4.5 mm. Pitch cones: tan(delta1) = z1/z2,
// R_e = m_e z1 / (2 sin delta1); with b = 2 R_e / 9 the mid-face module is
// m_m = m_e (R_e - b/2) / R_e = 4 mm, so the mean pitch diameter is 80 mm (the tooth-force
// validation case). Virtual (Tredgold) tooth numbers z_v = z / cos(delta).
TEST(GearGeometry, StraightBevelMidFaceAndVirtualGears) {
  GearPairSpec s;
  s.type = GearType::StraightBevel;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 4.5e-3;
  const double d1 = std::atan(0.5);
  const double re = 0.5 * 4.5e-3 * 20 / std::sin(d1);
  s.face_width_m = 2 * re / 9;
  s.outer_cone_distance_m = re;
  const GearPairGeometry g = gear_pair_geometry(s);
  EXPECT_NEAR(g.pinion.pitch_cone_angle_rad, d1, 1e-14);
  EXPECT_NEAR(g.wheel.pitch_cone_angle_rad, 0.5 * std::numbers::pi - d1, 1e-14);
  EXPECT_NEAR(g.outer_cone_distance_m, re, 1e-15);
  EXPECT_NEAR(g.mean_module_m, 4e-3, 1e-15);
  EXPECT_NEAR(g.pinion.mean_pitch_radius_m, 40e-3, 1e-15);
  EXPECT_NEAR(g.wheel.mean_pitch_radius_m, 80e-3, 1e-15);
  EXPECT_NEAR(g.pinion.virtual_teeth, 20 / std::cos(d1), 1e-12);
  EXPECT_NEAR(g.wheel.virtual_teeth, 40 / std::sin(d1), 1e-12);
  EXPECT_NEAR(g.pinion.pitch_radius_m, 40e-3 / std::cos(d1), 1e-15);
  EXPECT_NEAR(g.centre_distance_m, g.pinion.pitch_radius_m + g.wheel.pitch_radius_m, 1e-15);
  EXPECT_GT(g.transverse_contact_ratio, 1.0);
  // Inconsistent outer cone distance is refused.
  s.outer_cone_distance_m = 1.01 * re;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
}

// Non-right shaft angle: the pitch cones share their apex and touch along a common generator,
// so r_m = R_m sin(delta) for both members: sin(delta1) / sin(delta2) = z1 / z2, and
// delta1 + delta2 = Sigma.
TEST(GearGeometry, BevelPitchConesForObliqueShaftAngle) {
  GearPairSpec s;
  s.type = GearType::SpiralBevel;
  s.teeth_pinion = 17;
  s.teeth_wheel = 43;
  s.module_m = 5e-3;
  s.face_width_m = 25e-3;
  s.helix_angle_rad = 35 * kDeg;
  s.shaft_angle_rad = 75 * kDeg;
  const GearPairGeometry g = gear_pair_geometry(s);
  const double d1 = g.pinion.pitch_cone_angle_rad, d2 = g.wheel.pitch_cone_angle_rad;
  EXPECT_NEAR(d1 + d2, 75 * kDeg, 1e-14);
  EXPECT_NEAR(std::sin(d1) / std::sin(d2), 17.0 / 43.0, 1e-14);
  EXPECT_NEAR(g.pinion.mean_pitch_radius_m / std::sin(d1), g.mean_cone_distance_m, 1e-14);
  EXPECT_NEAR(g.wheel.mean_pitch_radius_m / std::sin(d2), g.mean_cone_distance_m, 1e-14);
  EXPECT_NEAR(g.normal_module_m, g.mean_module_m * std::cos(35 * kDeg), 1e-16);
  EXPECT_GT(g.overlap_ratio, 0.0);
}

// Hypoid: the members share the mean normal module, so r_m1 = r_m2 (z1/z2) cos(b2)/cos(b1).
TEST(GearGeometry, HypoidPinionEnlargement) {
  GearPairSpec s;
  s.type = GearType::Hypoid;
  s.teeth_pinion = 11;
  s.teeth_wheel = 41;
  s.module_m = 5e-3;
  s.face_width_m = 30e-3;
  s.helix_angle_rad = 30 * kDeg;
  s.pinion_spiral_angle_rad = 48 * kDeg;
  const GearPairGeometry g = gear_pair_geometry(s);
  EXPECT_NEAR(g.pinion.mean_pitch_radius_m,
              g.wheel.mean_pitch_radius_m * 11.0 / 41.0 * std::cos(30 * kDeg) / std::cos(48 * kDeg),
              1e-15);
  EXPECT_GT(g.pinion.mean_pitch_radius_m, g.wheel.mean_pitch_radius_m * 11.0 / 41.0);
  EXPECT_NEAR(g.helix_angle_rad, 39 * kDeg, 1e-14);
  // A pinion spiral angle on a non-hypoid pair is refused rather than ignored.
  s.type = GearType::SpiralBevel;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
}

TEST(GearGeometry, InvalidInputIsRefusedWithKeyPath) {
  GearPairSpec s = spur(0, 40, 3e-3);
  s.key_path = "gear_pairs[2]";
  try {
    gear_pair_geometry(s);
    FAIL() << "expected InputError";
  } catch (const geardyn::InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_pairs[2].teeth_pinion");
  }
  s = spur(20, 40, 3e-3);
  s.ratio = 2.1;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
  s.ratio = 2.0;
  EXPECT_NO_THROW(gear_pair_geometry(s));
  s = spur(20, 40, 3e-3);
  s.helix_angle_rad = 10 * kDeg;  // spur with a helix angle
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
  s = spur(20, 40, 3e-3);
  s.type = GearType::StraightBevel;
  s.mesh = MeshType::Internal;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
  s = spur(40, 30, 3e-3);
  s.mesh = MeshType::Internal;  // internal gear with fewer teeth than the pinion
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
  s = spur(20, 40, 3e-3);
  s.face_width_m = 0.0;
  EXPECT_THROW(gear_pair_geometry(s), geardyn::InputError);
}

// Stub teeth (addendum 0.4 m) on 20/40 teeth give eps_alpha ~ 0.7 < 1: refused, saying so.
TEST(GearGeometry, ContactRatioBelowOneIsAnInputError) {
  GearPairSpec s = spur(20, 40, 3e-3);
  s.addendum_coefficient = 0.4;
  try {
    gear_pair_geometry(s);
    FAIL() << "expected InputError";
  } catch (const geardyn::InputError& e) {
    EXPECT_NE(std::string(e.expected()).find("contact ratio"), std::string::npos);
    EXPECT_NE(std::string(e.found()).find("eps_alpha"), std::string::npos);
  }
}

// A 10-tooth pinion with standard addendum meshing with a 60-tooth gear undercuts: the wheel tip
// passes the pinion's interference point (z_min = 2 / sin^2(20 deg) ~ 17).
TEST(GearGeometry, InvoluteInterferenceIsAnInputError) {
  EXPECT_THROW(gear_pair_geometry(spur(10, 60, 3e-3)), geardyn::InputError);
}

TEST(GearGeometry, GeometryTableHasUnitsInColumnNames) {
  std::vector<GearPairGeometry> pairs{gear_pair_geometry(spur(20, 40, 3e-3)),
                                      gear_pair_geometry(spur(62, 62, 2e-3))};
  const geardyn::Table t = geometry_table(pairs);
  t.validate();
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_TRUE(t.has_column("pitch_radius_m"));
  EXPECT_TRUE(t.has_column("transverse_contact_ratio"));
  EXPECT_EQ(t.column("pitch_radius_m").unit, "m");
  EXPECT_NEAR(t.column("pitch_radius_m").numbers[1], 60e-3, 1e-15);
  EXPECT_EQ(t.column("member").texts[2], "pinion");
}

}  // namespace
