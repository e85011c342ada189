#pragma once
// Tooth forces of a gear mesh: tangential, radial and axial components on one member
// (docs/theory.md §11.2). F_t = T / r with r the reference radius (cylindrical gears) or the mean
// pitch radius at mid face (bevel and hypoid gears).
//
//   spur:        F_r = F_t tan(alpha)
//   helical:     F_r = F_t tan(alpha_n) / cos(beta),  F_a = F_t tan(beta)
//   bevel:       F_a = F_t / cos(beta) (tan(alpha_n) sin(delta) +- sin(beta) cos(delta))
//                F_r = F_t / cos(beta) (tan(alpha_n) cos(delta) -+ sin(beta) sin(delta))
//   (straight bevel: beta = 0; Gleason / AGMA 2005 formulas, e.g. Machinery's Handbook "Bevel
//   gear thrust"; hypoid: the same formula with each member's own spiral angle and pitch cone
//   angle, and F_t2 = F_t1 cos(beta_2) / cos(beta_1) because both members share the normal force —
//   an approximation that ignores the offset's effect on the cone geometry).
//
// Sign convention (all members, stated once here):
//   tangential_n  > 0: magnitude T / r of the tangential load.
//   radial_n      > 0: separating force, pushing the member's tooth towards its own axis (for an
//                      internal gear: away from its axis, i.e. again away from the mating gear).
//   axial_n, bevel > 0: away from the pitch-cone apex (out of mesh); < 0: towards the apex.
//   axial_n, helical: the magnitude F_t tan(beta); its direction along the axis follows from the
//                     hand of helix and the direction of the load and is not resolved here.
//
// Which bevel formula applies depends only on which flank of the member carries the load:
//   concave flank loaded -> upper signs: F_a = F_t/cos b (tan a sin d + sin b cos d) (out of mesh)
//   convex  flank loaded -> lower signs: F_a = F_t/cos b (tan a sin d - sin b cos d)
// (mirroring the member turns a right-hand into a left-hand gear but keeps concave concave and
// leaves axial and radial components unchanged; the spiral angle grows from toe to heel, so the
// concave flank faces the cutter centre and its load has an outward component along the cone
// generator). The loaded flank follows from hand of spiral, direction of rotation and whether the
// member drives (`loaded_flank`):
//   hand of spiral: right-hand when the outer half of a tooth is inclined clockwise from the axial
//     plane through the tooth's mid point, seen looking at the teeth from the apex side
//     (AGMA 1012 / ISO 23509 definition);
//   direction of rotation: seen from the back of the member (from the cone base, looking towards
//     the apex);
//   driving member: right hand + clockwise or left hand + counter-clockwise -> convex flank loaded;
//                   left hand + clockwise or right hand + counter-clockwise -> concave flank;
//   driven member: the opposite flank for the same hand and rotation. Mating bevel members have
//   opposite hands and (both seen from their own backs) opposite directions of rotation, so the
//   two rules agree: the convex flank of one member always carries the concave flank of the other.
//   Drive / coast: coasting (torque reversed, the nominal driven member drives) swaps the loaded
//   flanks; pass the member's role under the actual torque.
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"
#include "geardyn/gear/geometry.hpp"

namespace geardyn::gear {

enum class SpiralHand { Left, Right };
/// Direction of rotation seen from the back of the member (the cone base side for bevel gears),
/// looking towards the apex.
enum class Rotation { Clockwise, CounterClockwise };
enum class MemberRole { Driving, Driven };
enum class Flank { Concave, Convex };

std::string_view to_string(SpiralHand hand);
std::string_view to_string(Rotation rotation);
std::string_view to_string(MemberRole role);
std::string_view to_string(Flank flank);

SpiralHand opposite(SpiralHand hand);
Rotation opposite(Rotation rotation);
MemberRole opposite(MemberRole role);
Flank opposite(Flank flank);

/// The flank of a spiral bevel / hypoid member that carries the load (rule in the header comment).
Flank loaded_flank(SpiralHand hand, Rotation rotation, MemberRole role);

/// Force components on one member [N], sign convention in the header comment.
struct ToothForces {
  double tangential_n = 0.0;
  double radial_n = 0.0;
  double axial_n = 0.0;
};

/// F_t = T / r, F_r = F_t tan(alpha), F_a = 0. Throws std::invalid_argument for r <= 0 or
/// alpha outside (0, pi/2).
ToothForces spur_tooth_forces(double torque_nm, double pitch_radius_m, double pressure_angle_rad);

/// F_t = T / r, F_r = F_t tan(alpha_n) / cos(beta), F_a = F_t tan(beta) (r: transverse reference
/// radius z m_n / (2 cos beta)).
ToothForces helical_tooth_forces(double torque_nm, double pitch_radius_m,
                                 double normal_pressure_angle_rad, double helix_angle_rad);

/// Bevel / spiral bevel / hypoid member: F_t = T / r_m with the mean pitch radius, components as
/// in the header comment with the sign set by the loaded flank (irrelevant for beta = 0).
ToothForces bevel_tooth_forces(double torque_nm, double mean_pitch_radius_m,
                               double normal_pressure_angle_rad, double spiral_angle_rad,
                               double pitch_cone_angle_rad, Flank loaded);

/// Operating condition of a mesh, given for the pinion. Hand and rotation matter only for
/// spiral bevel and hypoid gears.
struct MeshLoadCase {
  std::string name = "load_case";
  double pinion_torque_nm = 0.0;  ///< |T1| > 0; the wheel torque follows from the forces
  MemberRole pinion_role = MemberRole::Driving;
  SpiralHand pinion_hand = SpiralHand::Left;
  Rotation pinion_rotation = Rotation::Clockwise;  ///< seen from the pinion's back
};

struct PairToothForces {
  ToothForces pinion, wheel;
  Flank pinion_flank = Flank::Concave;  ///< loaded flanks (spiral bevel / hypoid; else concave)
  Flank wheel_flank = Flank::Convex;
  double wheel_torque_nm = 0.0;  ///< F_t2 r_m2 (no losses)
  /// Ratios for splitting a tangential force harmonic into 3D components (per member).
  double pinion_radial_per_tangential = 0.0, pinion_axial_per_tangential = 0.0;
  double wheel_radial_per_tangential = 0.0, wheel_axial_per_tangential = 0.0;
};

/// Forces on both members of `geometry` for the pinion torque of `load`. Throws InputError for a
/// non-positive or non-finite torque.
PairToothForces tooth_forces(const GearPairGeometry& geometry, const MeshLoadCase& load);

/// One row per member and pair: pair, load_case, member, type, role, hand, rotation,
/// loaded_flank, torque_nm, tangential_force_n, radial_force_n, axial_force_n. `loads` must have
/// one entry per pair (std::invalid_argument otherwise).
Table tooth_force_table(const std::vector<GearPairGeometry>& pairs,
                        const std::vector<MeshLoadCase>& loads);

}  // namespace geardyn::gear
