#pragma once
// Checks shared by several analysis types, made after the model file is read (their
// AnalysisDeclaration::check): the gear pair an analysis names, the cyclic solid it works on.
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::analyses {

/// What a gear analysis asks of its [[gear_pairs]] entry.
struct GearPairUse {
  const std::string* pair = nullptr;  ///< the `pair` key (empty: the model's only pair)
  bool dynamic = false;               ///< the dynamic mesh model (needs both inertias)
  bool empty_allowed = false;         ///< several pairs and none named is fine (gear_pair: all)
  int gear = 0;                       ///< 1 or 2 with nodal_diameters: the loaded gear
  const std::vector<int>* nodal_diameters = nullptr;  ///< must fit that gear's teeth
};

/// The pair exists (or is the only one), the dynamic model has the inertias it needs, and the
/// nodal diameters fit the gear. (The geometry itself, interference and contact ratio, is
/// checked with the gear library before anything runs: check_gear_pairs and each type's
/// check_inputs.)
void check_gear_pair_use(const model::Analysis& a, const std::string& path,
                         const model::ModelCheck& check, const GearPairUse& use);

/// A rotor analysis excited at the mesh orders of a gear mesh (gear_forced_response,
/// gear_whine): `gear_mesh` names a [[gear_meshes]] entry (empty: the model's only one) with
/// teeth1 (its mesh frequency), a given `pair` has the same teeth, the `sensors` exist, and the
/// model has sensors at all. `type` names the analysis type in the messages.
void check_mesh_excitation(const std::string& path, const model::ModelCheck& check,
                           const std::string& type, const std::string& gear_mesh,
                           const std::string& pair, const std::vector<std::string>& sensors);

/// `solid` names a [[solids]] entry; with `cyclic`, one sector of a cyclic body (sectors >= 2)
/// whose nodal diameters fit. Returns the solid.
const model::Solid& check_solid_use(const std::string& path, const std::string& solid,
                                    const model::ModelCheck& check, bool cyclic,
                                    const std::vector<int>& nodal_diameters = {});

struct CyclicForcedResponseSettings;
/// A cyclic forced response (or a damper-ring response, which is one): its gear pair, a cyclic
/// solid, nodal diameters and engine orders that fit its sectors (k = +-h mod N), one tooth per
/// sector when a gear pair gives the tooth force.
void check_cyclic_forced_response(const model::Analysis& a, const std::string& path,
                                  const model::ModelCheck& check);

/// With the solids built: the node sets `sets` (key `master_sets`) exist in solid `solid_name`.
void check_master_sets(const Context& context, const std::string& solid_name,
                       const std::vector<std::string>& sets);

}  // namespace geardyn::analyses
