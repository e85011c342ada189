#pragma once
// mesh_harmonics: which engine-order harmonics of the tooth force, at one speed, excite each
// nodal diameter of a gear, in tangential, radial and axial components.
//
// At one speed: the dynamic mesh force over one mesh cycle, tiled to one revolution of the
// chosen gear, times the tooth-load window -> the filtered tooth force -> its order spectrum ->
// the engine-order harmonics k = h, N - h (...) per nodal diameter h, in tangential, radial and
// axial components (DESIGN 4.4-4.5; issue [mesh-excitation]): (model, settings) ->
// AnalysisOutput with tables, plots and notes. Bad input throws InputError (call
// check_gear_analyses, pair_model.hpp, before running, so it shows before any result); a
// numerical failure throws NumericalError naming the analysis.
#include <string>
#include <vector>

#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Engine-order harmonics of the tooth force of one gear at one speed (DESIGN 4.4).
struct MeshHarmonicsSettings : model::SettingsOf<MeshHarmonicsSettings> {
  std::string pair;
  double speed = 0.0;  ///< speed of gear 1 [rad/s]
  int gear = 1;        ///< 1 or 2: the gear whose teeth are loaded
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;
  double window_shift = 0.0;           ///< tooth-load window shift [pitches of that gear]
  double contact_ratio = model::kNaN;  ///< window contact ratio (NaN: the total contact ratio)
  std::vector<int> nodal_diameters;    ///< empty: 0 .. N / 2
  int orders_per_diameter = 2;         ///< orders k = +-h (mod N) per nodal diameter
  int max_order = 0;                   ///< order spectrum up to this (0: 2 N)
};

AnalysisOutput run_mesh_harmonics(const model::Model& model, const MeshHarmonicsSettings& settings,
                                  const std::string& name, Progress& progress = null_progress());

}  // namespace geardyn::analyses
