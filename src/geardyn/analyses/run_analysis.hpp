#pragma once
// Runs one analysis of a model through the registry: (model, analysis, context) -> Outcome
// (output: tables, plots, status; and the typed result). No global state, so a study can run
// many of these on threads.
#include <string>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Runs `analysis` of `model`. An analysis with `set` entries runs on its own variant of the
/// model, rebuilt from context.document(). Numerical failures are caught and returned as a
/// Failed status with the message; InputError propagates (bad input). The output carries the
/// analysis's name, type and run time.
Outcome run_analysis(const model::Model& model, const model::Analysis& analysis,
                     const Context& context);

/// Checks what the analyses ask of the model's built solids and files before anything runs
/// (each type's check_inputs): node sets, gear-pair geometry, measured files. InputError.
void check_inputs(const model::Model& model, const assembly::SolidComponents& solids);

}  // namespace geardyn::analyses
