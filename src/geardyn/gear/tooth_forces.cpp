#include "geardyn/gear/tooth_forces.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

void check_radius_angle(const char* what, double radius, double alpha) {
  if (!std::isfinite(radius) || radius <= 0.0)
    throw std::invalid_argument(fmt::format("{}: radius {} m is not > 0", what, radius));
  if (!std::isfinite(alpha) || alpha <= 0.0 || alpha >= 0.5 * units::kPi)
    throw std::invalid_argument(
        fmt::format("{}: pressure angle {} rad is outside (0, pi/2)", what, alpha));
}

}  // namespace

std::string_view to_string(SpiralHand hand) { return hand == SpiralHand::Left ? "left" : "right"; }
std::string_view to_string(Rotation rotation) {
  return rotation == Rotation::Clockwise ? "cw" : "ccw";
}
std::string_view to_string(MemberRole role) {
  return role == MemberRole::Driving ? "driving" : "driven";
}
std::string_view to_string(Flank flank) { return flank == Flank::Concave ? "concave" : "convex"; }

SpiralHand opposite(SpiralHand hand) {
  return hand == SpiralHand::Left ? SpiralHand::Right : SpiralHand::Left;
}
Rotation opposite(Rotation rotation) {
  return rotation == Rotation::Clockwise ? Rotation::CounterClockwise : Rotation::Clockwise;
}
MemberRole opposite(MemberRole role) {
  return role == MemberRole::Driving ? MemberRole::Driven : MemberRole::Driving;
}
Flank opposite(Flank flank) { return flank == Flank::Concave ? Flank::Convex : Flank::Concave; }

Flank loaded_flank(SpiralHand hand, Rotation rotation, MemberRole role) {
  // Right hand turning clockwise seen from the back moves its teeth so that the flank facing the
  // motion is the convex one; a driving member pushes with that leading flank, a driven member is
  // pushed on its trailing flank. Left hand or counter-clockwise each mirror the picture once.
  const bool rh_cw_like = (hand == SpiralHand::Right) == (rotation == Rotation::Clockwise);
  const Flank driving = rh_cw_like ? Flank::Convex : Flank::Concave;
  return role == MemberRole::Driving ? driving : opposite(driving);
}

ToothForces spur_tooth_forces(double torque_nm, double pitch_radius_m, double pressure_angle_rad) {
  check_radius_angle("spur_tooth_forces", pitch_radius_m, pressure_angle_rad);
  ToothForces f;
  f.tangential_n = torque_nm / pitch_radius_m;
  f.radial_n = f.tangential_n * std::tan(pressure_angle_rad);
  return f;
}

ToothForces helical_tooth_forces(double torque_nm, double pitch_radius_m,
                                 double normal_pressure_angle_rad, double helix_angle_rad) {
  check_radius_angle("helical_tooth_forces", pitch_radius_m, normal_pressure_angle_rad);
  if (!std::isfinite(helix_angle_rad) || std::abs(helix_angle_rad) >= 0.5 * units::kPi)
    throw std::invalid_argument(fmt::format(
        "helical_tooth_forces: helix angle {} rad outside (-pi/2, pi/2)", helix_angle_rad));
  ToothForces f;
  f.tangential_n = torque_nm / pitch_radius_m;
  f.radial_n = f.tangential_n * std::tan(normal_pressure_angle_rad) / std::cos(helix_angle_rad);
  f.axial_n = f.tangential_n * std::abs(std::tan(helix_angle_rad));
  return f;
}

ToothForces bevel_tooth_forces(double torque_nm, double mean_pitch_radius_m,
                               double normal_pressure_angle_rad, double spiral_angle_rad,
                               double pitch_cone_angle_rad, Flank loaded) {
  check_radius_angle("bevel_tooth_forces", mean_pitch_radius_m, normal_pressure_angle_rad);
  if (!std::isfinite(spiral_angle_rad) || spiral_angle_rad < 0.0 ||
      spiral_angle_rad >= 0.5 * units::kPi)
    throw std::invalid_argument(
        fmt::format("bevel_tooth_forces: spiral angle {} rad outside [0, pi/2)", spiral_angle_rad));
  if (!std::isfinite(pitch_cone_angle_rad) || pitch_cone_angle_rad <= 0.0 ||
      pitch_cone_angle_rad >= 0.5 * units::kPi)
    throw std::invalid_argument(fmt::format(
        "bevel_tooth_forces: pitch cone angle {} rad outside (0, pi/2)", pitch_cone_angle_rad));
  const double ft = torque_nm / mean_pitch_radius_m;
  const double tan_a = std::tan(normal_pressure_angle_rad);
  const double sb = std::sin(spiral_angle_rad);
  const double cb = std::cos(spiral_angle_rad);
  const double sd = std::sin(pitch_cone_angle_rad);
  const double cd = std::cos(pitch_cone_angle_rad);
  const double s = loaded == Flank::Concave ? 1.0 : -1.0;
  ToothForces f;
  f.tangential_n = ft;
  f.axial_n = ft / cb * (tan_a * sd + s * sb * cd);
  f.radial_n = ft / cb * (tan_a * cd - s * sb * sd);
  return f;
}

PairToothForces tooth_forces(const GearPairGeometry& g, const MeshLoadCase& load) {
  if (!std::isfinite(load.pinion_torque_nm) || load.pinion_torque_nm <= 0.0)
    throw InputError(g.spec.where, g.spec.key_path + ".pinion_torque",
                     "a finite pinion torque > 0 N·m (direction through role and rotation)",
                     fmt::format("{}", load.pinion_torque_nm));
  PairToothForces p;
  const double t1 = load.pinion_torque_nm;
  const double alpha_n = g.normal_pressure_angle_rad;
  switch (g.spec.type) {
    case GearType::Spur: {
      p.pinion = spur_tooth_forces(t1, g.pinion.mean_pitch_radius_m, alpha_n);
      p.wheel_torque_nm = p.pinion.tangential_n * g.wheel.mean_pitch_radius_m;
      p.wheel = spur_tooth_forces(p.wheel_torque_nm, g.wheel.mean_pitch_radius_m, alpha_n);
      break;
    }
    case GearType::Helical: {
      const double beta = g.helix_angle_rad;
      p.pinion = helical_tooth_forces(t1, g.pinion.mean_pitch_radius_m, alpha_n, beta);
      p.wheel_torque_nm = p.pinion.tangential_n * g.wheel.mean_pitch_radius_m;
      p.wheel = helical_tooth_forces(p.wheel_torque_nm, g.wheel.mean_pitch_radius_m, alpha_n, beta);
      break;
    }
    case GearType::StraightBevel:
    case GearType::SpiralBevel:
    case GearType::Hypoid: {
      p.pinion_flank = loaded_flank(load.pinion_hand, load.pinion_rotation, load.pinion_role);
      p.wheel_flank = opposite(p.pinion_flank);
      p.pinion =
          bevel_tooth_forces(t1, g.pinion.mean_pitch_radius_m, alpha_n, g.pinion.spiral_angle_rad,
                             g.pinion.pitch_cone_angle_rad, p.pinion_flank);
      // Both members carry the same normal force F_n = F_t / (cos(alpha_n) cos(beta)).
      const double ft2 = p.pinion.tangential_n * std::cos(g.wheel.spiral_angle_rad) /
                         std::cos(g.pinion.spiral_angle_rad);
      p.wheel_torque_nm = ft2 * g.wheel.mean_pitch_radius_m;
      p.wheel =
          bevel_tooth_forces(p.wheel_torque_nm, g.wheel.mean_pitch_radius_m, alpha_n,
                             g.wheel.spiral_angle_rad, g.wheel.pitch_cone_angle_rad, p.wheel_flank);
      break;
    }
  }
  p.pinion_radial_per_tangential = p.pinion.radial_n / p.pinion.tangential_n;
  p.pinion_axial_per_tangential = p.pinion.axial_n / p.pinion.tangential_n;
  p.wheel_radial_per_tangential = p.wheel.radial_n / p.wheel.tangential_n;
  p.wheel_axial_per_tangential = p.wheel.axial_n / p.wheel.tangential_n;
  return p;
}

Table tooth_force_table(const std::vector<GearPairGeometry>& pairs,
                        const std::vector<MeshLoadCase>& loads) {
  if (pairs.size() != loads.size())
    throw std::invalid_argument(fmt::format("tooth_force_table: {} gear pairs but {} load cases",
                                            pairs.size(), loads.size()));
  Table t;
  t.name = "tooth_forces";
  t.title = "Tooth forces per gear pair (radial > 0 separating, bevel axial > 0 away from apex)";
  std::vector<std::string> pair, load_case, member, type, role, hand, rotation, flank;
  std::vector<double> torque, ft, fr, fa;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const GearPairGeometry& g = pairs[i];
    const MeshLoadCase& l = loads[i];
    const PairToothForces p = tooth_forces(g, l);
    const bool spiral = g.spec.type == GearType::SpiralBevel || g.spec.type == GearType::Hypoid;
    for (int k = 0; k < 2; ++k) {
      const bool pin = k == 0;
      const ToothForces& f = pin ? p.pinion : p.wheel;
      pair.push_back(g.spec.name);
      load_case.push_back(l.name);
      member.push_back(pin ? "pinion" : "wheel");
      type.emplace_back(to_string(g.spec.type));
      role.emplace_back(to_string(pin ? l.pinion_role : opposite(l.pinion_role)));
      if (spiral) {
        hand.emplace_back(to_string(pin ? l.pinion_hand : opposite(l.pinion_hand)));
        rotation.emplace_back(to_string(pin ? l.pinion_rotation : opposite(l.pinion_rotation)));
        flank.emplace_back(to_string(pin ? p.pinion_flank : p.wheel_flank));
      } else {
        hand.emplace_back("-");
        rotation.emplace_back("-");
        flank.emplace_back("-");
      }
      torque.push_back(pin ? l.pinion_torque_nm : p.wheel_torque_nm);
      ft.push_back(f.tangential_n);
      fr.push_back(f.radial_n);
      fa.push_back(f.axial_n);
    }
  }
  t.add_text("pair", std::move(pair));
  t.add_text("load_case", std::move(load_case));
  t.add_text("member", std::move(member));
  t.add_text("type", std::move(type));
  t.add_text("role", std::move(role));
  t.add_text("hand", std::move(hand));
  t.add_text("rotation", std::move(rotation));
  t.add_text("loaded_flank", std::move(flank));
  t.add("torque_nm", "N·m", std::move(torque));
  t.add("tangential_force_n", "N", std::move(ft));
  t.add("radial_force_n", "N", std::move(fr));
  t.add("axial_force_n", "N", std::move(fa));
  return t;
}

}  // namespace geardyn::gear
