#pragma once
// Key groups shared by several analysis types: each function makes one key (type, unit, default,
// range, help) without its setter; the analysis type adds `.to_settings(&MySettings::member)`.
// A new analysis type that needs a speed range, modes, sensors or a gear pair reuses these.
#include <vector>

#include "geardyn/model/model.hpp"
#include "geardyn/model/schema.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {

/// `speed_rpm` (used by modal, harmonic, transient).
model::keys::F reference_speed_key();

/// `speed_rpm` (used by campbell, unbalance, cyclic_modal, mesh_force, cyclic_forced_response,
/// gear_forced_response, damper_ring_response).
model::keys::F speed_list_key();

/// `speed_start_rpm` (used by campbell, unbalance, cyclic_modal, mesh_force,
/// cyclic_forced_response, gear_forced_response, damper_ring_response).
model::keys::F speed_start_rpm_key();

/// `speed_stop_rpm` (used by campbell, unbalance, cyclic_modal, mesh_force, cyclic_forced_response,
/// gear_forced_response, damper_ring_response).
model::keys::F speed_stop_rpm_key();

/// `speed_count` (used by campbell, unbalance, cyclic_modal, mesh_force, cyclic_forced_response,
/// gear_forced_response, damper_ring_response).
model::keys::F speed_count_key();

/// `gear_mesh`, `max_mesh_order`, `residual_vectors` (used by gear_forced_response, gear_whine).
model::keys::F excited_gear_mesh_key();
model::keys::F max_mesh_order_key();
model::keys::F residual_vectors_key();

/// `n_modes` (used by modal, campbell, solid_modal, cyclic_modal, reduction,
/// cyclic_forced_response, gear_forced_response, damper_ring_response).
model::keys::F n_modes_key();

/// `solid` (used by solid_modal, cyclic_modal, reduction, cyclic_forced_response,
/// damper_ring_response).
model::keys::F solid_key();

/// `shapes` (used by solid_modal, cyclic_modal).
model::keys::F shapes_key();

/// `reduction` (used by cyclic_modal, reduction, cyclic_forced_response, damper_ring_response).
model::keys::F reduction_key();

/// `reduced_modes` (used by cyclic_modal, reduction, cyclic_forced_response, damper_ring_response).
model::keys::F reduced_modes_key();

/// `master_sets` (used by cyclic_modal, reduction, cyclic_forced_response, damper_ring_response).
model::keys::F master_sets_key();

/// `method` (used by modal, campbell).
model::keys::F method_key();

/// `spacing` (used by harmonic, sweep).
model::keys::F spacing_key();

/// `unbalances` (used by unbalance, transient).
model::keys::F unbalances_key();

/// `sensors` (used by harmonic, unbalance, transient, gear_forced_response).
model::keys::F sensors_key();

/// `threads`: worker threads over the points of a frequency or speed sweep (used by harmonic,
/// unbalance, campbell).
model::keys::F point_threads_key();

/// `pair` (used by gear_pair, mesh_force, mesh_harmonics).
model::keys::F gear_pair_name_key();

/// `model` (used by mesh_force, mesh_harmonics, cyclic_forced_response, damper_ring_response).
model::keys::F mesh_model_key();

/// `contact_loss` (used by mesh_force, mesh_harmonics, cyclic_forced_response,
/// damper_ring_response).
model::keys::F contact_loss_key();

/// `gear` (used by mesh_harmonics, cyclic_forced_response, damper_ring_response).
model::keys::F gear_key();

/// `window_shift` (used by mesh_harmonics, cyclic_forced_response, damper_ring_response).
model::keys::F window_shift_key();

/// `contact_ratio` (used by mesh_harmonics, cyclic_forced_response, damper_ring_response).
model::keys::F contact_ratio_key();

/// `nodal_diameters` (used by mesh_harmonics, cyclic_forced_response).
model::keys::F nodal_diameters_key();

/// `orders_per_diameter` (used by mesh_harmonics, cyclic_forced_response).
model::keys::F orders_per_diameter_key();

/// `min_prominence_db` (used by correlation, cyclic_forced_response, gear_forced_response).
model::keys::F min_prominence_db_key();

/// `pair` (used by cyclic_forced_response, gear_forced_response, damper_ring_response).
model::keys::F forced_pair_key();

/// `force_amplitude` (used by cyclic_forced_response, gear_forced_response, damper_ring_response).
model::keys::F force_amplitude_key();

/// `harmonics_rpm` (used by cyclic_forced_response, damper_ring_response).
model::keys::F harmonics_rpm_key();

/// `force_direction` (used by cyclic_forced_response, damper_ring_response).
model::keys::F force_direction_key();

/// `cone_apex` (used by cyclic_forced_response, damper_ring_response).
model::keys::F cone_apex_key();

/// `excitation_set` (used by cyclic_forced_response, damper_ring_response).
model::keys::F excitation_set_key();

/// `sensor_sets` (used by cyclic_forced_response, damper_ring_response).
model::keys::F sensor_sets_key();

/// `sensor_nodes` (used by cyclic_forced_response, damper_ring_response).
model::keys::F sensor_nodes_key();

/// `sensor_components` (used by cyclic_forced_response, damper_ring_response).
model::keys::F sensor_components_key();

/// `damping_ratio` (used by cyclic_forced_response, damper_ring_response).
model::keys::F damping_ratio_key();

/// `q_factor` (used by cyclic_forced_response, damper_ring_response).
model::keys::F q_factor_key();

/// `measured_file` (used by cyclic_forced_response, gear_forced_response).
model::keys::F measured_file_key();

/// `measured_sensor` (used by cyclic_forced_response, gear_forced_response).
model::keys::F measured_sensor_key();

/// `scale_to_measured` (used by cyclic_forced_response, gear_forced_response).
model::keys::F scale_to_measured_key();

/// Speeds [rad/s] from speed_rpm = [...] or speed_start_rpm / speed_stop_rpm / speed_count.
std::vector<double> speed_range(const model::TableContext& t);
/// speed_range() for an analysis that needs every speed > 0; `why` completes "speeds > 0 rpm
/// (...)". The error names the key the file gave (speed_rpm or speed_start_rpm).
std::vector<double> positive_speed_range(const model::TableContext& t, const std::string& why);
/// The speed-range alternatives: speed_rpm, or start / stop / count (`required`: one of them).
model::Choice speed_range_choice(bool required);
/// Integers of a number-array value (nodal diameters, node ids, orders).
std::vector<int> integers_of(const model::FieldValue& v);
/// Amplitudes of a number-or-array value.
std::vector<double> amplitudes_of(const model::FieldValue& v);

enum class ReductionMethod;
/// The `reduction` choice ("none", "guyan", "craig_bampton") as a ReductionMethod.
ReductionMethod reduction_method(const model::FieldValue& v);

struct CyclicForcedResponseSettings;
/// The cross-key rules of the tooth-force excitation keys (cyclic_forced_response and
/// damper_ring_response).
void finish_tooth_excitation(CyclicForcedResponseSettings& s, const model::TableContext& t);

/// The keys every forced response of a cyclic sector shares (cyclic_forced_response and
/// damper_ring_response, whose settings extend CyclicForcedResponseSettings): speeds, solid and
/// reduction, the tooth-force source (gear pair or explicit amplitude), excitation and sensor
/// points, modal damping.
std::vector<model::Field> cyclic_sector_response_keys();

}  // namespace geardyn::analyses
