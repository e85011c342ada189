#pragma once
// gear_forced_response: how strongly a rotor model vibrates over speed under the mesh-order
// harmonics of one of its gear meshes, at its sensors.
//
// A forced response to gear-mesh excitation, wired to the model file (issue [mesh-excitation]
// sections 6 and 7; DESIGN 4.3-4.5): (model, settings) -> AnalysisOutput with tables, plots and
// notes. Bad input throws InputError (call check_forced_analyses, cyclic_forced_response.hpp,
// before running, so it shows before any result); a numerical failure throws NumericalError
// naming the analysis.
//
// A rotor with a [[gear_meshes]] entry, excited along the line of action at mesh orders
// p = 1 .. n with amplitudes F_p (response::run_mesh_forced_response, modal basis of n_modes
// modes at zero speed plus the static residual vector). F_p is the blocked mesh force of a
// [[gear_pairs]] entry (analyses::blocked_mesh_force_harmonics: F_s k(t) / k_mean, harmonic p,
// = k_mean e_p to first order) or given (force_amplitude).
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Forced response of a rotor model to the mesh-order harmonics of one of its [[gear_meshes]]
/// over speed (forced/rotor_mesh_response.hpp, modal method).
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

AnalysisOutput run_gear_forced_response(const model::Model& model, const fe::LinearSystem& system,
                                        const GearForcedResponseSettings& settings,
                                        const std::string& name,
                                        Progress& progress = null_progress());

}  // namespace geardyn::analyses
