#pragma once
// Model -> assembled linear system, the first step of every analysis (DESIGN 3):
// fe::assemble (DOF map, sparse M, C, K, G) followed by eig::apply_modal_damping (the low-rank
// modal damping term from the undamped modes at zero speed, when the model asks for it).
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analysis {

/// Throws InputError for inconsistent models and NumericalError("modal damping", ...) when the
/// undamped modes that carry modal damping cannot be computed.
fe::LinearSystem build_system(const model::Model& model);

}  // namespace geardyn::analysis
