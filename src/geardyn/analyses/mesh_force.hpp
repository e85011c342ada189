#pragma once
// mesh_force: how large the dynamic mesh force of a gear pair gets over a speed range, where
// the mesh resonance lies and where the teeth lose contact.
//
// The dynamic mesh model over a speed range of gear 1, swept up and/or down: dynamic factor, DTE
// and contact loss versus speed, the mesh resonance speed (f_n = sqrt(k_mean / m_e) / 2 pi), time
// histories at `detail_rpm` (docs/theory.md §12-13; issue [mesh-excitation]): run_mesh_force solves
// (MeshForceResult), mesh_force_output writes tables, plots and notes. Bad input throws InputError
// (call check_gear_pairs and the type's own input check, through analyses::check_inputs, before
// running, so it shows before any result); a numerical failure throws NumericalError naming the
// analysis, or, where the rest of the result is still worth having (a speed sweep), comes back as a
// non-Ok status with every failed point listed in the message.
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The direction(s) a mesh_force sweep runs through its speeds.
enum class SweepDirectionKind { Up, Down, Both };

/// What the mesh damper acts on (gear::MeshDamping).
enum class MeshDampingKind { Dte, ElasticDeflection };

/// The dynamic mesh force over a speed range of gear 1 (docs/theory.md §13).
struct MeshForceSettings : model::SettingsOf<MeshForceSettings> {
  std::string pair;            ///< empty: the model's only gear pair
  std::vector<double> speeds;  ///< speeds of gear 1 [rad/s], increasing
  SweepDirectionKind direction = SweepDirectionKind::Both;
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;           ///< false: linear mesh law for every x
  std::vector<double> detail_speeds;  ///< time histories at these speeds of gear 1 [rad/s]
  MeshDampingKind damping_on = MeshDampingKind::Dte;
  double force_amplitude = 0.0;  ///< F_a of the external harmonic force [N]
  int force_order = 1;           ///< its frequency in mesh orders (an integer >= 1)
  double force_phase = 0.0;      ///< its phase at the cycle start [rad]
};

/// The steady state at one of the `detail_rpm` speeds.
struct MeshForceDetail {
  double speed = 0.0;  ///< of gear 1 [rad/s]
  gear::MeshResponse response;
};

/// The swept steady states of the mesh, its constants and the detailed time histories.
struct MeshForceResult {
  PairModel pair;
  gear::MeshSweepResult sweep;
  double mean_stiffness_n_m = 0.0;            ///< k_mean of the mesh model
  double damping_n_s_m = 0.0;                 ///< c
  double equivalent_mass_kg = 0.0;            ///< m_e (dynamic model)
  double natural_frequency_hz = model::kNaN;  ///< sqrt(k_mean / m_e) / 2 pi (NaN: no dynamics)
  std::vector<MeshForceDetail> details;       ///< in the order of detail_rpm
};

/// Input checks that need the gear pair's STE (InputError at the analysis's keys): damping on
/// the elastic deflection needs a continuous unloaded TE.
void check_mesh_force_inputs(const model::Model& model, const MeshForceSettings& settings,
                             const Context& context);

MeshForceResult run_mesh_force(const model::Model& model, const MeshForceSettings& settings,
                               const Context& context);

AnalysisOutput mesh_force_output(const model::Model& model, const MeshForceSettings& settings,
                                 const MeshForceResult& result, const Context& context);

}  // namespace geardyn::analyses
