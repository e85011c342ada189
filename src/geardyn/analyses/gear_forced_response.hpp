#pragma once
// gear_forced_response: how strongly a rotor model vibrates over speed under the mesh-order
// harmonics of one of its gear meshes, at its sensors.
//
// A forced response to gear-mesh excitation, wired to the model file (issue [mesh-excitation]
// sections 6 and 7; docs/theory.md §11-13): run_gear_forced_response solves (model, settings,
// context)
// -> GearForcedResponseResult; gear_forced_response_output writes its tables, plots and notes.
// Bad input throws InputError located by the context (check_gear_forced_response_inputs runs
// before any analysis, through analyses::check_inputs, so it shows before any result); a numerical
// failure throws NumericalError naming the analysis.
//
// A rotor with a [[gear_meshes]] entry, excited along the line of action at mesh orders
// p = 1 .. n with amplitudes F_p (response::run_mesh_forced_response, modal basis of n_modes
// modes at zero speed plus the static residual vector). F_p is the blocked mesh force of a
// [[gear_pairs]] entry (analyses::blocked_mesh_force_harmonics: F_s k(t) / k_mean, harmonic p,
// = k_mean e_p to first order) or given (force_amplitude).
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"

namespace geardyn::analyses {

/// Forced response of a rotor model to the mesh-order harmonics of one of its [[gear_meshes]]
/// over speed (response/rotor_mesh_response.hpp, modal method).
struct GearForcedResponseSettings : model::SettingsOf<GearForcedResponseSettings> {
  std::string gear_mesh;                ///< [[gear_meshes]] name (empty: the only one)
  std::string pair;                     ///< [[gear_pairs]] entry (empty: force_amplitude)
  std::vector<double> force_amplitude;  ///< [N]: one for every order, or one per order
  int max_mesh_order = 3;               ///< orders 1 .. this
  std::vector<std::string> sensors;     ///< empty: all
  std::vector<double> speeds;           ///< reference speeds [rad/s]
  int n_modes = 10;
  bool residual_vectors = true;
  std::string measured_file;    ///< measured response over speed (empty: none)
  std::string measured_sensor;  ///< sensor compared (empty: the first)
  int measured_mesh_order = 0;  ///< curve compared: this mesh order (0: the sum of the orders)
  bool scale_to_measured = false;
  double min_prominence_db = 6.0;
};

/// What run_gear_forced_response solves: the response per mesh order over speed (with its
/// peaks), and where the mesh-order forces came from.
struct GearForcedResponseResult {
  response::RotorForcedResult response;
  bool from_pair = false;            ///< forces from the gear pair (else force_amplitude)
  double pair_static_force_n = 0.0;  ///< F_s of the pair [N] (from_pair)
  std::string pair_ste_source;       ///< where the pair's STE came from (from_pair)

  /// The largest amplitude over speed of the sum of the mesh orders' amplitudes at sensor
  /// `sensor` (index into response.sensors) [m or rad].
  double peak_amplitude(std::size_t sensor) const;
  /// Index of the sensor called `name` in response.sensors (empty: the first);
  /// std::runtime_error if it has none.
  std::size_t sensor_index(const std::string& name) const;
};

/// Solves the mesh-order forced response (the rotor's system from context.system()).
GearForcedResponseResult run_gear_forced_response(const model::Model& model,
                                                  const GearForcedResponseSettings& settings,
                                                  const Context& context);

/// Its tables (mesh_resonances, mesh_forced_response, mesh_order_forces, the measured
/// comparison), plots and notes.
AnalysisOutput gear_forced_response_output(const model::Model& model,
                                           const GearForcedResponseSettings& settings,
                                           const GearForcedResponseResult& result,
                                           const Context& context);

/// What the parser cannot check: the measured file reads, and the gear pair's STE resolves
/// max_mesh_order. Throws InputError located by `context`.
void check_gear_forced_response_inputs(const model::Model& model,
                                       const GearForcedResponseSettings& settings,
                                       const Context& context);

}  // namespace geardyn::analyses
