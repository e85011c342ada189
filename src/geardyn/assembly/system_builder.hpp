#pragma once
// Model -> assembled linear system, the first step of every analysis (docs/architecture.md, "Data
// flow"): the solids joined to the rotor by spiders reduced to bodies
// (component/solid_coupling.hpp), fe::assemble (DOF map, sparse M, C, K, G, the bodies joined) and
// assembly::apply_modal_damping (the low-rank modal damping term from the undamped modes at zero
// speed, when the model asks for it).
#include <vector>

#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::assembly {

/// `solids`: the model's solids already built (assembly::build_solids), or null: the joined
/// solids are built here. Throws InputError for inconsistent models (and bad joints of solids),
/// NumericalError("modal damping", ...) when the undamped modes that carry modal damping cannot
/// be computed, and NumericalError("craig_bampton", ...) when a joined solid cannot be reduced.
fe::LinearSystem build_system(const model::Model& model,
                              const assembly::SolidComponents* solids = nullptr,
                              Progress& progress = null_progress());

/// The same, keeping the joined solids' reductions in `coupled` (model order): what expands the
/// system's response to the solids' nodes (e.g. a housing's surface velocities).
fe::LinearSystem build_system(const model::Model& model, const assembly::SolidComponents* solids,
                              std::vector<CoupledSolid>& coupled,
                              Progress& progress = null_progress());

}  // namespace geardyn::assembly
