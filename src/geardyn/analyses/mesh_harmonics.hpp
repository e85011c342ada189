#pragma once
// mesh_harmonics: which engine-order harmonics of the tooth force, at one speed, excite each
// nodal diameter of a gear, in tangential, radial and axial components.
//
// At one speed: the dynamic mesh force over one mesh cycle, tiled to one revolution of the
// chosen gear, times the tooth-load window -> the filtered tooth force -> its order spectrum ->
// the engine-order harmonics k = h, N - h (...) per nodal diameter h, in tangential, radial and
// axial components (docs/theory.md §12-13; issue [mesh-excitation]): run_mesh_harmonics solves
// (MeshHarmonicsResult), mesh_harmonics_output writes tables, plots and notes. Bad input throws
// InputError (call
// check_gear_pairs and the type's own input check, through analyses::check_inputs, before running,
// so it shows before any result); a numerical failure throws NumericalError naming the analysis.
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Engine-order harmonics of the tooth force of one gear at one speed (docs/theory.md §12.2).
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

/// The tooth force over one revolution, its order spectrum and its harmonics per nodal diameter.
struct MeshHarmonicsResult {
  PairModel pair;
  ToothForceRevolution revolution;
  int max_order = 0;  ///< of the order spectrum
  /// Tangential amplitude [N] of orders 0 .. max_order of the tooth force (0: the mean).
  std::vector<double> order_amplitude_n;
  std::vector<int> diameters;  ///< nodal diameters of `harmonics`
  std::vector<gear::HarmonicComponents> harmonics;
};

MeshHarmonicsResult run_mesh_harmonics(const model::Model& model,
                                       const MeshHarmonicsSettings& settings,
                                       const Context& context);

AnalysisOutput mesh_harmonics_output(const model::Model& model,
                                     const MeshHarmonicsSettings& settings,
                                     const MeshHarmonicsResult& result, const Context& context);

/// Checks made before anything runs: the tooth-load window's contact ratio (in [1, 3] and below
/// the teeth) and max_order (resolved by the samples of one revolution). InputError.
void check_mesh_harmonics_inputs(const model::Model& model, const MeshHarmonicsSettings& settings,
                                 const Context& context);

}  // namespace geardyn::analyses
