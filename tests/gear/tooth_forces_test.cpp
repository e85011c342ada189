// Tooth forces: spur, helical, straight and spiral bevel (all hand / rotation / flank cases),
// hypoid, and the per-pair table.
//
// Reference figures: the [mesh-excitation] issue, computed from the formulas of docs/theory.md
// §11.2 (Gleason / AGMA 2005 bevel thrust formulas as printed in Machinery's Handbook). They are
// given to 10 significant digits, so they are checked to 1e-9 relative; the computation itself
// rounds at ~1e-15.
#include "geardyn/gear/tooth_forces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

using namespace geardyn::gear;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kRel = 1e-9;

void expect_rel(double computed, double reference) {
  EXPECT_LE(std::abs(computed - reference), kRel * std::abs(reference))
      << "computed " << computed << " reference " << reference;
}

// Spur: T1 = 100 N·m on a pinion z1 = 20, m = 3 mm (r = 30 mm), alpha = 20 deg.
//   F_t = 100 / 0.03 = 3333.333333 N, F_r = F_t tan(20 deg) = 1213.234114 N.
TEST(ToothForces, SpurReference) {
  const ToothForces f = spur_tooth_forces(100.0, 0.5 * 20 * 3e-3, 20 * kDeg);
  expect_rel(f.tangential_n, 3333.333333333);
  expect_rel(f.radial_n, 1213.234114);
  EXPECT_EQ(f.axial_n, 0.0);
}

// Helical: m_n = 3 mm, alpha_n = 20 deg, beta = 15 deg, z1 = 20: r = z m_n / (2 cos beta).
//   F_t = 3219.752754 N, F_r = F_t tan(alpha_n)/cos(beta) = 1213.234114 N,
//   F_a = F_t tan(beta) = 862.730150 N.
TEST(ToothForces, HelicalReference) {
  const double r = 0.5 * 20 * 3e-3 / std::cos(15 * kDeg);
  const ToothForces f = helical_tooth_forces(100.0, r, 20 * kDeg, 15 * kDeg);
  expect_rel(f.tangential_n, 3219.752754);
  expect_rel(f.radial_n, 1213.234114);
  expect_rel(f.axial_n, 862.730150);
}

// Same figures through the geometry of a helical pair (r from m_n, z, beta).
TEST(ToothForces, HelicalReferenceThroughGeometry) {
  GearPairSpec s;
  s.type = GearType::Helical;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.helix_angle_rad = 15 * kDeg;
  s.face_width_m = 30e-3;
  MeshLoadCase l;
  l.pinion_torque_nm = 100.0;
  const PairToothForces p = tooth_forces(gear_pair_geometry(s), l);
  expect_rel(p.pinion.tangential_n, 3219.752754);
  expect_rel(p.pinion.radial_n, 1213.234114);
  expect_rel(p.pinion.axial_n, 862.730150);
  // Action and reaction: the wheel carries the same components, and T2 = T1 z2/z1.
  expect_rel(p.wheel.tangential_n, p.pinion.tangential_n);
  expect_rel(p.wheel.axial_n, p.pinion.axial_n);
  expect_rel(p.wheel_torque_nm, 200.0);
}

// Straight bevel: Sigma = 90 deg, z = 20/40 (delta1 = atan(1/2)), mean pitch diameter 80 mm,
// T1 = 200 N·m: F_t = 5000 N, F_a = F_t tan(alpha) sin(delta1) = 813.862186 N,
// F_r = F_t tan(alpha) cos(delta1) = 1627.724371 N.
TEST(ToothForces, StraightBevelReference) {
  const double d1 = std::atan(20.0 / 40.0);
  for (Flank flank : {Flank::Concave, Flank::Convex}) {  // no spiral: flank is irrelevant
    const ToothForces f = bevel_tooth_forces(200.0, 0.04, 20 * kDeg, 0.0, d1, flank);
    expect_rel(f.tangential_n, 5000.0);
    expect_rel(f.axial_n, 813.862186);
    expect_rel(f.radial_n, 1627.724371);
  }
}

// Spiral bevel, beta = 35 deg, otherwise as above:
//   concave flank loaded: F_a = 4124.965583 N (out of mesh), F_r = 421.372896 N;
//   convex flank loaded:  F_a = -2137.881033 N (towards the apex), F_r = 3552.796204 N.
// Sign logic (tooth_forces.hpp): the driving member with right hand + cw or left hand + ccw
// (seen from its back) loads its convex flank, left + cw or right + ccw its concave flank; a driven
// member loads the opposite flank. All four hand/rotation cases of the driving pinion, and the
// driven pinion for each, are checked.
struct SpiralCase {
  SpiralHand hand;
  Rotation rotation;
  MemberRole role;
  Flank expected_flank;
  double axial, radial;
};

TEST(ToothForces, SpiralBevelAllHandRotationFlankCases) {
  const double d1 = std::atan(20.0 / 40.0);
  const double concave_a = 4124.965583, concave_r = 421.372896;
  const double convex_a = -2137.881033, convex_r = 3552.796204;
  const SpiralCase cases[] = {
      {SpiralHand::Right, Rotation::Clockwise, MemberRole::Driving, Flank::Convex, convex_a,
       convex_r},
      {SpiralHand::Left, Rotation::CounterClockwise, MemberRole::Driving, Flank::Convex, convex_a,
       convex_r},
      {SpiralHand::Left, Rotation::Clockwise, MemberRole::Driving, Flank::Concave, concave_a,
       concave_r},
      {SpiralHand::Right, Rotation::CounterClockwise, MemberRole::Driving, Flank::Concave,
       concave_a, concave_r},
      {SpiralHand::Right, Rotation::Clockwise, MemberRole::Driven, Flank::Concave, concave_a,
       concave_r},
      {SpiralHand::Left, Rotation::CounterClockwise, MemberRole::Driven, Flank::Concave, concave_a,
       concave_r},
      {SpiralHand::Left, Rotation::Clockwise, MemberRole::Driven, Flank::Convex, convex_a,
       convex_r},
      {SpiralHand::Right, Rotation::CounterClockwise, MemberRole::Driven, Flank::Convex, convex_a,
       convex_r},
  };
  for (const SpiralCase& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.hand)) + " " + std::string(to_string(c.rotation)) + " " +
                 std::string(to_string(c.role)));
    const Flank flank = loaded_flank(c.hand, c.rotation, c.role);
    EXPECT_EQ(flank, c.expected_flank);
    const ToothForces f = bevel_tooth_forces(200.0, 0.04, 20 * kDeg, 35 * kDeg, d1, flank);
    expect_rel(f.tangential_n, 5000.0);
    expect_rel(f.axial_n, c.axial);
    expect_rel(f.radial_n, c.radial);
  }
}

// Independent check of the sign logic between mating members. With Sigma = 90 deg the pinion
// axis is the wheel's radial direction at the mesh and vice versa, so the one contact force gives
//   pinion axial thrust = wheel radial force,  pinion radial force = wheel axial thrust
// (both "away from the mating member"). This holds only if the wheel, which has the opposite
// hand and turns the opposite way, loads the opposite flank.
//        wheel axis
//            |
//   apex  ---+-----  pinion axis
TEST(ToothForces, SpiralBevelPairForceBalanceAtRightShaftAngle) {
  GearPairSpec s;
  s.type = GearType::SpiralBevel;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 4.5e-3;
  s.helix_angle_rad = 35 * kDeg;
  s.face_width_m = 2 * (0.5 * 4.5e-3 * 20 / std::sin(std::atan(0.5))) / 9;  // d_m1 = 80 mm
  const GearPairGeometry g = gear_pair_geometry(s);
  for (SpiralHand hand : {SpiralHand::Left, SpiralHand::Right})
    for (Rotation rot : {Rotation::Clockwise, Rotation::CounterClockwise})
      for (MemberRole role : {MemberRole::Driving, MemberRole::Driven}) {
        MeshLoadCase l;
        l.pinion_torque_nm = 200.0;
        l.pinion_hand = hand;
        l.pinion_rotation = rot;
        l.pinion_role = role;
        const PairToothForces p = tooth_forces(g, l);
        EXPECT_EQ(p.wheel_flank, opposite(p.pinion_flank));
        // The wheel's own rule (opposite hand, opposite rotation, opposite role) agrees.
        EXPECT_EQ(p.wheel_flank, loaded_flank(opposite(hand), opposite(rot), opposite(role)));
        expect_rel(p.pinion.tangential_n, 5000.0);
        expect_rel(p.wheel.tangential_n, 5000.0);
        EXPECT_NEAR(p.pinion.axial_n, p.wheel.radial_n, 1e-9 * 5000);
        EXPECT_NEAR(p.pinion.radial_n, p.wheel.axial_n, 1e-9 * 5000);
        const double expected_axial = p.pinion_flank == Flank::Concave ? 4124.965583 : -2137.881033;
        expect_rel(p.pinion.axial_n, expected_axial);
        expect_rel(p.wheel_torque_nm, 400.0);
      }
}

// Hypoid: both members carry the same normal force, so F_t2 = F_t1 cos(beta2) / cos(beta1), and
// each member's components use its own spiral and pitch cone angle.
TEST(ToothForces, HypoidSharesTheNormalForce) {
  GearPairSpec s;
  s.type = GearType::Hypoid;
  s.teeth_pinion = 11;
  s.teeth_wheel = 41;
  s.module_m = 5e-3;
  s.face_width_m = 30e-3;
  s.helix_angle_rad = 30 * kDeg;
  s.pinion_spiral_angle_rad = 48 * kDeg;
  const GearPairGeometry g = gear_pair_geometry(s);
  MeshLoadCase l;
  l.pinion_torque_nm = 150.0;
  const PairToothForces p = tooth_forces(g, l);
  const double fn1 = p.pinion.tangential_n / (std::cos(20 * kDeg) * std::cos(48 * kDeg));
  const double fn2 = p.wheel.tangential_n / (std::cos(20 * kDeg) * std::cos(30 * kDeg));
  EXPECT_NEAR(fn1, fn2, 1e-12 * fn1);
  const ToothForces direct =
      bevel_tooth_forces(150.0, g.pinion.mean_pitch_radius_m, 20 * kDeg, 48 * kDeg,
                         g.pinion.pitch_cone_angle_rad, p.pinion_flank);
  EXPECT_NEAR(p.pinion.axial_n, direct.axial_n, 1e-12 * std::abs(direct.axial_n));
}

TEST(ToothForces, TableOfTwoPairs) {
  GearPairSpec spur;
  spur.name = "stage1";
  spur.teeth_pinion = 20;
  spur.teeth_wheel = 40;
  spur.module_m = 3e-3;
  spur.face_width_m = 20e-3;
  GearPairSpec bevel;
  bevel.name = "stage2";
  bevel.type = GearType::SpiralBevel;
  bevel.teeth_pinion = 20;
  bevel.teeth_wheel = 40;
  bevel.module_m = 4.5e-3;
  bevel.helix_angle_rad = 35 * kDeg;
  bevel.face_width_m = 2 * (0.5 * 4.5e-3 * 20 / std::sin(std::atan(0.5))) / 9;
  MeshLoadCase l1;
  l1.pinion_torque_nm = 100.0;
  MeshLoadCase l2;
  l2.pinion_torque_nm = 200.0;
  l2.pinion_hand = SpiralHand::Left;
  l2.pinion_rotation = Rotation::Clockwise;
  const geardyn::Table t =
      tooth_force_table({gear_pair_geometry(spur), gear_pair_geometry(bevel)}, {l1, l2});
  t.validate();
  ASSERT_EQ(t.rows(), 4u);
  expect_rel(t.column("radial_force_n").numbers[0], 1213.234114);
  expect_rel(t.column("axial_force_n").numbers[2], 4124.965583);
  EXPECT_EQ(t.column("loaded_flank").texts[2], "concave");
  EXPECT_EQ(t.column("loaded_flank").texts[3], "convex");
  EXPECT_EQ(t.column("hand").texts[3], "right");
  EXPECT_EQ(t.column("axial_force_n").unit, "N");
  EXPECT_THROW(tooth_force_table({gear_pair_geometry(spur)}, {}), std::invalid_argument);
}

TEST(ToothForces, NonPositiveTorqueIsAnInputError) {
  GearPairSpec s;
  s.teeth_pinion = 20;
  s.teeth_wheel = 40;
  s.module_m = 3e-3;
  s.face_width_m = 20e-3;
  MeshLoadCase l;
  l.pinion_torque_nm = 0.0;
  EXPECT_THROW(tooth_forces(gear_pair_geometry(s), l), geardyn::InputError);
}

}  // namespace
