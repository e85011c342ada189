#pragma once
// gear_pair: the geometry, tooth forces, ISO 6336 mesh stiffness and static transmission error
// of the [[gear_pairs]] of a model, before any dynamics.
//
// Geometry, tooth forces (drive and coast, both members), ISO 6336-1 stiffness, and the STE /
// mesh stiffness over one mesh cycle of each pair (docs/theory.md §11-13; issue [mesh-excitation]):
// run_gear_pair builds the pairs (GearPairResult), gear_pair_output writes their tables, plots
// and notes. Bad input throws InputError (call check_gear_pairs and the type's own input check,
// through analyses::check_inputs, before running, so it shows before any result).
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Geometry, tooth forces, ISO 6336 stiffness and the mesh stiffness / STE over one mesh cycle.
struct GearPairSettings : model::SettingsOf<GearPairSettings> {
  std::string pair;  ///< empty: every [[gear_pairs]] entry
};

/// The pairs analysed, in the order of [[gear_pairs]] (or the one named).
struct GearPairResult {
  std::vector<PairModel> pairs;  ///< point into the model's [[gear_pairs]]
};

/// Mean mesh stiffness k_mean = F_s mean(1 / (e - e_g)) [N/m] of the STE the dynamic model uses.
double mean_mesh_stiffness(const PairModel& pm);

/// Natural frequency of the mesh, sqrt(k_mean / m_e) / 2 pi [Hz]; NaN without both inertias.
double mesh_natural_frequency_hz(const PairModel& pm);

GearPairResult run_gear_pair(const model::Model& model, const GearPairSettings& settings,
                             const Context& context);

AnalysisOutput gear_pair_output(const model::Model& model, const GearPairSettings& settings,
                                const GearPairResult& result, const Context& context);

}  // namespace geardyn::analyses
