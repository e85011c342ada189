#pragma once
// The force map of a gear pair for the tooth-contact element of the drivetrain transient
// (elements/gear_mesh_contact.hpp, docs/theory.md §16.6): unloaded TE and loaded approach over
// one period of the pinion angle at several line-of-action forces, from the pair's STE source:
//   * the loaded tooth contact analysis (ste_source = "tooth_contact"): the LTCA at the torques
//     MeshForceMapOptions::torque_factors x the pair's torque, over the hunting period when the
//     pair has pitch deviations (the LTCA's cycles), with the pair's contact settings;
//   * an imported LTCA table (ltca_file): its torques at the pair's mounting errors;
//   * an STE file (ste_file): its torques; one curve: a linear mesh through the pair's force;
//   * the synthetic ISO 6336 STE: a linear mesh at the pair's force.
// Sample 0 is at the pinion angle 0 and is the STE's sample 0 (after ste_shift), as for the
// linear gear analyses (analyses/pair_model.hpp).
#include <cstddef>
#include <vector>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/elements/gear_mesh_contact.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct MeshForceMapOptions {
  /// LTCA route: the torques as multiples of the pair's torque (increasing, > 0). 0.25 and 0.5
  /// resolve the softer, Hertzian low-load end (where a rattling mesh works), 1 is the
  /// operating point (exact there), 1.5 and 2 cover a dynamic factor up to 2 (ISO 6336-1's
  /// K_v range); beyond 2 the last slope is extrapolated, the contact pattern being complete.
  std::vector<double> torque_factors{0.25, 0.5, 1.0, 1.5, 2.0};
};

/// The map of pair `pm` (built by build_pair_model). InputError at the pair's key that selects
/// the source (`ste_source`, `ltca_file`, `ste_file`) for an LTCA that fails at a torque or a
/// force-approach law that is not monotone.
elements::MeshForceMap mesh_force_map(const model::Model& model, const PairModel& pm,
                                      const MeshForceMapOptions& options = {});

/// The map of [[gear_meshes]] entry `mesh_index`: its contact's `gear_pair`, or without one the
/// constant `stiffness` (one angle, no unloaded TE; period 2 pi / teeth1, or 2 pi without
/// teeth). InputError at `gear_meshes[i].stiffness` when neither is given.
elements::MeshForceMap mesh_force_map(const model::Model& model, std::size_t mesh_index,
                                      const MeshForceMapOptions& options = {});

}  // namespace geardyn::analyses
