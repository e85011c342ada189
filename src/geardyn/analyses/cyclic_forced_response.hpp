#pragma once
// cyclic_forced_response: how strongly a cyclic solid (a gear) vibrates over its speed range
// under the engine-order harmonics of its tooth force, per nodal diameter and engine order.
//
// A forced response to gear-mesh excitation, wired to the model file (issue [mesh-excitation]
// sections 6 and 7; docs/theory.md §10-13): run_cyclic_forced_response solves (model, settings,
// context)
// -> CyclicForcedResponseResult; cyclic_forced_response_output writes its tables, plots and
// notes. Bad input throws InputError located by the context (analyses::check_inputs runs
// check_cyclic_forced_response_inputs before running, so it shows before any result); a numerical
// failure throws NumericalError naming the analysis.
//
// One sector of a cyclic solid (a gear, one tooth per sector when a gear pair loads it) in the
// frame turning with it. Per nodal diameter h the modes are solved once
// (cyclic::solve_cyclic_modes, optionally on a Craig-Bampton sector whose masters are the
// interfaces, the excitation and the sensor nodes); every engine order k with k = +-h (mod N) is
// then a modal sum per speed (response::run_cyclic_forced_response):
//   u_0(W) = sum_r psi_r (psi_r^H f_0) / (w_r^2 - (k W)^2 + 2 i zeta w_r k W).
// The tooth-force harmonics F_k come from a [[gear_pairs]] entry exactly as mesh_harmonics
// computes them (analyses::tooth_force_over_revolution: dynamic mesh force at one speed,
// tooth-load window, order spectrum, 3D split), or are given (force_amplitude).
// Load directions at an excitation node x of sector 0 (unit vectors e_r = radial outwards,
// e_theta = z x e_r): tangential -e_theta (the load presses the flank facing +theta, where
// meshgen::gear_sector puts its "excitation" node), radial -e_r (positive radial force pushes
// the tooth towards its axis, gear/tooth_forces.hpp), axial +z when the pitch-cone apex is on the
// -z side (positive axial force points away from the apex). The load is shared equally by the
// nodes of the excitation set.
// Optional measured curve over speed (gear::read_measured_response_csv, displacement): peak
// speed, amplitude and Q compared, and the force scaling that matches the peak.
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/analyses/solid_common.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"

namespace geardyn::analyses {

/// Forced response of a cyclic solid to the engine-order harmonics of its tooth force, over the
/// speed of that solid, by modal summation per (nodal diameter, engine order) (docs/theory.md §10,
/// §12.4; response/cyclic_forced_response.hpp). The harmonics come from a [[gear_pairs]] entry
/// (computed as mesh_harmonics does) or are given as force_amplitude.
struct CyclicForcedResponseSettings : model::SettingsOf<CyclicForcedResponseSettings> {
  std::string solid;
  std::string pair;  ///< [[gear_pairs]] entry (empty: force_amplitude)
  int gear = 1;      ///< 1 or 2: the member of the pair the solid is
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;
  double window_shift = 0.0;             ///< [pitches]
  double contact_ratio = model::kNaN;    ///< window contact ratio (NaN: total contact ratio)
  double harmonics_speed = model::kNaN;  ///< gear-1 speed of the dynamic mesh force [rad/s]
  std::vector<double> force_amplitude;   ///< [N]: one for every order, or one per engine order
  std::optional<model::Vec3> force_direction;  ///< of an explicit force (empty: tangential)
  bool apex_below = true;                      ///< the pitch-cone apex lies on the -z side
  std::vector<int> nodal_diameters;            ///< empty: 0 .. sectors / 2
  std::vector<int> engine_orders;              ///< empty: orders_per_diameter orders per diameter
  int orders_per_diameter = 2;
  std::string excitation_set = "excitation";
  std::vector<std::string> sensor_sets;
  std::vector<int> sensor_nodes;  ///< node ids of the mesh
  std::vector<model::Component> sensor_components = {model::Component::Ux, model::Component::Uy,
                                                     model::Component::Uz};
  double damping_ratio = model::kNaN;  ///< zeta of every mode ...
  double q_factor = model::kNaN;       ///< ... or Q = 1 / (2 zeta)
  std::vector<double> speeds;          ///< speeds of the solid [rad/s]
  int n_modes = 10;                    ///< modes per nodal diameter
  ReductionMethod reduction = ReductionMethod::None;
  int cb_modes = 40;
  std::vector<std::string> master_sets;
  bool superpose = true;
  std::string measured_file;      ///< measured response over speed (empty: none)
  std::string measured_sensor;    ///< sensor compared (empty: the first)
  int measured_engine_order = 0;  ///< curve compared: this order (0: the superposed sum)
  bool scale_to_measured = false;
  double min_prominence_db = 6.0;
};

/// One excited (nodal diameter h, engine order k) with its tooth-force harmonic.
struct CyclicOrderForce {
  int nodal_diameter = 0;
  int engine_order = 0;
  std::complex<double> tangential, radial, axial;  ///< pair: tooth_forces.hpp components [N]
  double amplitude = 0.0;                          ///< explicit force_amplitude [N] (pair: NaN)
};

/// What run_cyclic_forced_response solves.
struct CyclicForcedResponseResult {
  response::CyclicForcedResult response;  ///< scaled to the measurement if scale_to_measured
  cyclic::CyclicModesResult modes;        ///< per nodal diameter
  std::vector<CyclicOrderForce> orders;   ///< the excitation, in the order of response.orders
  std::string force_note;                 ///< where the harmonics come from
  std::string reduction_note;             ///< what the Craig-Bampton reduction kept (or empty)
  /// The measured curve compared (measured_file), the computed curve it is compared with
  /// (unscaled), the sensor and order (-1: the sum) of that curve, and the force scale applied
  /// (scale_to_measured; 1: none).
  std::optional<gear::MeasuredResponse> measured;
  std::vector<double> measured_computed;
  std::size_t measured_sensor = 0;
  int measured_order = -1;
  double scale = 1.0;

  /// Index of the sensor called `name` (empty: the first); std::runtime_error if none.
  std::size_t sensor_index(const std::string& name) const;
  /// The superposed amplitude (sum over the orders) at sensor `k` over speed [m or rad].
  std::vector<double> sum_curve(std::size_t k) const;
};

/// Solves the forced response of the cyclic solid s.solid (from context.solid()).
CyclicForcedResponseResult run_cyclic_forced_response(const model::Model& model,
                                                      const CyclicForcedResponseSettings& settings,
                                                      const Context& context);

/// Its tables (cyclic_resonances, cyclic_forced_response, harmonic_forces, the measured
/// comparison, cyclic_response_peaks, cyclic_modes), plots and notes.
AnalysisOutput cyclic_forced_response_output(const model::Model& model,
                                             const CyclicForcedResponseSettings& settings,
                                             const CyclicForcedResponseResult& result,
                                             const Context& context);

/// What the parser cannot check for a cyclic forced response (or a damper-ring response, whose
/// settings extend these): the node sets and node ids it names exist in the solid built before
/// the run (context.solids()) and carry DOFs, the solid is a mesh (not a reduced file), the
/// tooth-load window of its gear pair fits, and the measured file reads and holds a
/// displacement over speed. Throws InputError located by `context`.
void check_cyclic_forced_response_inputs(const model::Model& model,
                                         const CyclicForcedResponseSettings& settings,
                                         const Context& context);

}  // namespace geardyn::analyses
