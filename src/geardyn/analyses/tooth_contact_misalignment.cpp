#include "geardyn/analyses/tooth_contact_misalignment.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geardyn/analyses/tooth_contact.hpp"

namespace geardyn::analyses {

double ContactMisalignment::deflection_at(double torque_nm) const {
  if (!deflection) return 0.0;
  return deflection->misalignment_m * torque_nm / reference_torque_nm;
}

ContactMisalignment contact_misalignment(const model::Model& model, const PairModel& pm) {
  const model::GearPair& p = *pm.pair;
  const model::ContactModelSpec& c = p.contact;
  const double alpha = pm.geometry.working_pressure_angle_rad;
  ContactMisalignment m;
  m.given_m = c.misalignment + c.axis_inclination_deviation * std::sin(alpha) +
              c.axis_deviation * std::cos(alpha);
  m.reference_torque_nm = p.torque;
  if (c.deflection_mesh.empty()) return m;
  // The pinion's tooth forces at the pair's torque (gear 1 drives, drive flank).
  const gear::ToothForces& f = pm.drive_forces.pinion;
  assembly::MeshToothLoad load;
  load.tangential_n = f.tangential_n;
  load.radial_n = f.radial_n;
  load.axial_n = f.axial_n;
  m.deflection = assembly::mesh_static_deflection(
      model, c.deflection_mesh, load, pm.geometry.face_width_m,
      c.where.line > 0 ? c.where : p.where, pm.key_path + ".contact.deflection_mesh");
  return m;
}

gear::ToothContactResult solve_contact(const ToothContactModel& tc, double torque_nm) {
  const double f = tc.misalignment.at(torque_nm);
  if (!tc.misalignment.deflection || f == tc.options.misalignment_in_plane_m)
    return tc.contact->solve(torque_nm);
  // The deflection part scales with the torque: the same contact model with that misalignment.
  gear::ToothContactOptions options = tc.options;
  options.misalignment_in_plane_m = f;
  gear::GearPairGeometry keyed = tc.pair.geometry;
  keyed.spec.key_path = tc.pair.key_path;
  const gear::ToothContact contact(keyed, tc.pinion, tc.wheel, *tc.compliance, options);
  return contact.solve(torque_nm);
}

std::string misalignment_note(const ToothContactModel& tc) {
  const ContactMisalignment& m = tc.misalignment;
  const std::string& name = tc.pair.pair->name;
  const std::string given = fmt::format(
      "given f_ma = {:.6g} m (misalignment + f_Sigma_delta sin(alpha_wt) + f_Sigma_beta "
      "cos(alpha_wt))",
      m.given_m);
  if (!m.deflection)
    return fmt::format(
        "'{}': mesh misalignment in the plane of action f_ma = {:.6g} m, {}; the out-of-plane "
        "component is not modelled (it moves the contact along the profile, a second-order "
        "effect on the gap).",
        name, m.given_m, given);
  const assembly::MeshDeflection& d = *m.deflection;
  return fmt::format(
      "'{}': mesh misalignment in the plane of action f_ma = {:.6g} m at T1 = {:.6g} N m: {} "
      "plus {:.6g} m from the static deflection of the rotor under the pair's tooth forces "
      "(gear mesh '{}' without its spring, torsion held; docs/theory.md §15.7; proportional to "
      "the torque at the other torques). Slopes of the gear axes in the plane of action (along "
      "the line of action per unit face position y): gear 1 at node '{}' {:.6g} rad, gear 2 at "
      "node '{}' {:.6g} rad; out of the plane of action {:.6g} rad and {:.6g} rad, an "
      "out-of-plane misalignment of {:.6g} m that is not modelled (it moves the contact along "
      "the profile, a second-order effect on the gap). Face position y = 0 is the face end at "
      "({:.4g}, {:.4g}, {:.4g}) x b/2 from the pitch point (global).",
      name, m.at(m.reference_torque_nm), m.reference_torque_nm, given, d.misalignment_m, d.mesh,
      d.gear1, d.slope1_rad, d.gear2, d.slope2_rad, d.out_of_plane_slope1_rad,
      d.out_of_plane_slope2_rad, d.out_of_plane_misalignment_m, -d.face_direction.x(),
      -d.face_direction.y(), -d.face_direction.z());
}

}  // namespace geardyn::analyses
