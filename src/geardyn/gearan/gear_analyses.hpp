#pragma once
// Analyses of the gear mesh-excitation chain on the [[gear_pairs]] of a model
// (DESIGN 4.4-4.5; issue [mesh-excitation]): (model, settings) -> AnalysisOutput with tables,
// plots and notes. Bad input throws InputError (call check_gear_analyses before running, so it
// shows before any result); a numerical failure throws NumericalError naming the analysis, or,
// where the rest of the result is still worth having (a speed sweep), comes back as a non-Ok
// status with every failed point listed in the message.
//
//   gear_pair       geometry, tooth forces (drive and coast, both members), ISO 6336-1
//                   stiffness, and the STE / mesh stiffness over one mesh cycle of each pair
//   mesh_force      the dynamic mesh model over a speed range of gear 1, swept up and/or down:
//                   dynamic factor, DTE and contact loss versus speed, the mesh resonance speed
//                   (f_n = sqrt(k_mean / m_e) / 2 pi), time histories at `detail_rpm`
//   mesh_harmonics  at one speed: the dynamic mesh force over one mesh cycle, tiled to one
//                   revolution of the chosen gear, times the tooth-load window -> the filtered
//                   tooth force -> its order spectrum -> the engine-order harmonics k = h, N - h
//                   (...) per nodal diameter h, in tangential, radial and axial components
//   correlation     resonance peaks of a measured response, Q by the half-power method with
//                   interpolated crossings, and the comparison with a reference peak
#include <string>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gearan/pair_model.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::gearan {

AnalysisOutput run_gear_pair(const model::Model& model, const model::GearPairSettings& settings,
                             const std::string& name, Progress& progress = null_progress());

AnalysisOutput run_mesh_force(const model::Model& model, const model::MeshForceSettings& settings,
                              const std::string& name, Progress& progress = null_progress());

AnalysisOutput run_mesh_harmonics(const model::Model& model,
                                  const model::MeshHarmonicsSettings& settings,
                                  const std::string& name, Progress& progress = null_progress());

AnalysisOutput run_correlation(const model::Model& model,
                               const model::CorrelationSettings& settings, const std::string& name,
                               Progress& progress = null_progress());

}  // namespace geardyn::gearan
