#pragma once
// The mesh misalignment f_ma of a loaded tooth contact analysis (docs/theory.md §15.3, §15.7):
// the one given in [gear_pairs.contact] (misalignment + f_Sigma_delta sin(alpha_wt) +
// f_Sigma_beta cos(alpha_wt)) plus, with `deflection_mesh`, the part from the static deflection
// of the rotor model under the pair's tooth forces (assembly/static_deflection.hpp). The static
// problem is linear, so that part is computed once at the pair's torque and scales with the
// analysed torque: f_ma(T) = given + f_defl(T_pair) T / T_pair.
#include <optional>
#include <string>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/assembly/static_deflection.hpp"
#include "geardyn/gear/tooth_contact.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct ToothContactModel;

struct ContactMisalignment {
  double given_m = 0.0;                                ///< from the keys
  std::optional<assembly::MeshDeflection> deflection;  ///< at reference_torque_nm
  double reference_torque_nm = 0.0;                    ///< the pair's torque T_pair
  /// The part from the deflection at pinion torque T [m] (0 without deflection_mesh).
  double deflection_at(double torque_nm) const;
  /// f_ma used at pinion torque T [m].
  double at(double torque_nm) const { return given_m + deflection_at(torque_nm); }
};

/// The misalignment of pair `pm` (InputError at `[gear_pairs.contact].deflection_mesh` for a
/// mesh the rotor does not have or cannot carry statically).
ContactMisalignment contact_misalignment(const model::Model& model, const PairModel& pm);

/// The contact analysis of `tc` at pinion torque T with the misalignment at that torque.
gear::ToothContactResult solve_contact(const ToothContactModel& tc, double torque_nm);

/// The note of the tooth_contact output: f_ma at the pair's torque, where it comes from, and
/// with a deflection the slopes of both gear nodes in and out of the plane of action.
std::string misalignment_note(const ToothContactModel& tc);

}  // namespace geardyn::analyses
