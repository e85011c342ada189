#pragma once
// One [[gear_pairs]] entry of a model turned into the inputs of the gear library (docs/theory.md
// §11-13): the geometry (gear::gear_pair_geometry), the ISO 6336-1 stiffness options, the tooth
// forces for drive and coast, and the static transmission error that drives the dynamic mesh model
// — read from the pair's `ste_file`, interpolated in an imported LTCA table (`ltca_file`), from
// the loaded tooth contact analysis, or synthetic, e = F_s / k, from the ISO 6336 mesh stiffness
// curve.
//
// Conventions (stated once here, used by every gear analysis):
//   * gear 1 is the pinion and carries `torque`; its speed is the speed of the analyses;
//   * base radii r_b,i = r_m,i cos(alpha_t) (cylindrical gears: r_i cos(alpha_t), the base
//     radius; bevel / hypoid: the real mean radius projected on the line of action of the
//     virtual gear, as gear::synthetic_ste does);
//   * F_s = T / r_b1 along the line of action, m_e = J1 J2 / (J1 r_b2^2 + J2 r_b1^2);
//   * an STE file's angle abscissa is gear 1's rotation; angular STE is scaled by r_b1;
//   * sample 0 of the STE is the tooth entering contact, after the pair's `ste_shift`.
// Errors from the gear library are reported with the model's key names
// (`gear_pairs[0].teeth2`, not `teeth_wheel`) at the pair's table.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/geometry.hpp"
#include "geardyn/gear/mesh_stiffness.hpp"
#include "geardyn/gear/ste.hpp"
#include "geardyn/gear/tooth_forces.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Everything the gear analyses need about one pair. Keeps a pointer to the model's GearPair.
struct PairModel {
  const model::GearPair* pair = nullptr;
  std::size_t index = 0;  ///< position in Model::gear_pairs
  std::string key_path;   ///< "gear_pairs[<index>]"
  gear::GearPairGeometry geometry;
  gear::MeshLoadCase drive, coast;  ///< pinion driving / driven under |torque|
  gear::PairToothForces drive_forces, coast_forces;
  gear::IsoStiffnessOptions iso_options;
  gear::MeshStiffnessCurve stiffness;  ///< ISO 6336 based curve over one mesh cycle
  std::optional<gear::SteCurve> ste;   ///< the STE the dynamic model uses (after ste_shift)
  bool ste_from_file = false;
  bool ste_from_contact = false;   ///< from the loaded tooth contact analysis (ste_source)
  bool ste_from_ltca = false;      ///< from an imported LTCA table (ltca_file)
  std::filesystem::path ste_path;  ///< resolved ste_file or ltca_file (empty: synthetic)
  double base_radius1_m = 0.0, base_radius2_m = 0.0;  ///< r_b1, r_b2 (see above)
  double static_force_n = 0.0;                        ///< F_s = T / r_b1

  /// Where the STE comes from, for tables and notes: "file <name>", "LTCA table <name>",
  /// "loaded tooth contact analysis" or "synthetic, ISO 6336".
  std::string ste_source_label() const;
  /// m_e from the pair's inertias; InputError at the pair when they are missing.
  double equivalent_mass_kg() const;
  /// Options of the dynamic mesh model for this pair (mass only for the dynamic model).
  gear::DynamicMeshOptions mesh_options(MeshForceModel model, bool contact_loss) const;
};

/// Builds and checks pair `index` of `model`. Throws InputError (model key names, the pair's
/// location, or the STE file's line and column) for a geometry the gear library rejects, an
/// unreadable or inconsistent STE file, or a torque outside the file's torques.
PairModel build_pair_model(const model::Model& model, std::size_t index);

/// The pair an analysis names (`name` empty: the model's only pair). The parser has checked it.
std::size_t pair_index(const model::Model& model, const std::string& name);

/// A file name of the model, relative to the model file's folder.
std::filesystem::path resolve_model_path(const model::Model& model, const std::string& file);

/// Checks every gear pair of `model` before anything runs (geometry, contact ratio, STE file):
/// builds each; InputError at the pair for the first problem.
void check_gear_pairs(const model::Model& model);

}  // namespace geardyn::analyses
