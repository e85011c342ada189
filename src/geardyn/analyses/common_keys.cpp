#include "geardyn/analyses/common_keys.hpp"

#include "geardyn/analyses/cyclic_forced_response.hpp"

namespace geardyn::analyses {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

F reference_speed_key() {
  return number("speed_rpm", kRpm,
                "Reference speed (transient: constant speed, or run-up start speed).")
      .def("0.0")
      .ge(0);
}

F speed_list_key() {
  return numbers("speed_rpm", kRpm, "Reference speeds, increasing.")
      .required()
      .ge(0)
      .increasing()
      .min_items(1);
}

F speed_start_rpm_key() {
  return number("speed_start_rpm", kRpm, "First speed of an evenly spaced range.").required().ge(0);
}

F speed_stop_rpm_key() {
  return number("speed_stop_rpm", kRpm, "Last speed of the range (> speed_start_rpm).")
      .required()
      .ge(0);
}

F speed_count_key() {
  return integer("speed_count", "Number of speeds in the range.").def("51").ge(2).le(100000);
}

F excited_gear_mesh_key() {
  return text("gear_mesh", "The [[gear_meshes]] entry of the rotor that is excited.")
      .note("the model's only gear mesh");
}

F max_mesh_order_key() {
  return integer("max_mesh_order", "Mesh orders 1 .. this are excited.").def("3").ge(1).le(100);
}

F residual_vectors_key() {
  return boolean("residual_vectors",
                 "Add the static response to the mesh load to the modal basis (static "
                 "correction of the modes left out).")
      .def("true");
}

F n_modes_key() {
  return integer("n_modes",
                 "Number of modes computed (cyclic_modal, cyclic_forced_response: per nodal "
                 "diameter; reduction: full-model modes compared with the reduced ones; "
                 "gear_forced_response: modes of the modal basis).")
      .def("10")
      .ge(1)
      .le(10000);
}

F solid_key() {
  return reference("solid", Ref::Solid, "The [[solids]] component analysed.").required();
}

F shapes_key() {
  return integer("shapes",
                 "Mode shapes written as VTU and Gmsh views (per nodal diameter "
                 "for cyclic_modal; 0: none).")
      .def("6")
      .ge(0)
      .le(1000);
}

F reduction_key() {
  return choice("reduction", {"none", "guyan", "craig_bampton"},
                "Sector reduction before the cyclic solve (cyclic_modal), or the method of "
                "a reduction analysis.")
      .def("\"craig_bampton\"")
      .note("cyclic_modal, cyclic_forced_response, damper_ring_response: \"none\"");
}

F reduced_modes_key() {
  return integer("reduced_modes", "Fixed-interface (Craig-Bampton) modes kept.")
      .def("40")
      .ge(0)
      .le(100000);
}

F master_sets_key() {
  return F("master_sets", FieldType::StringArray,
           "Node sets kept as physical masters (contact, excitation, sensor, connection "
           "nodes); cyclic_modal adds the sector interfaces itself, "
           "cyclic_forced_response the interfaces, the excitation and the sensor nodes, "
           "damper_ring_response also the contact pairs.")
      .def("[]");
}

F method_key() {
  return choice("method", {"auto", "dense", "sparse"},
                "Eigen solver: dense for small models, sparse shift-invert Lanczos / "
                "Arnoldi for large ones, auto chooses by size.")
      .def("\"auto\"");
}

F spacing_key() {
  return choice("spacing", {"linear", "log"},
                "Spacing of the frequencies (harmonic) or sweep values (sweep; log also "
                "draws a log axis).")
      .def("\"linear\"");
}

F unbalances_key() {
  return names("unbalances", Ref::Unbalance, "Unbalances applied.").note("all unbalances");
}

F sensors_key() { return names("sensors", Ref::Sensor, "Sensors reported.").note("all sensors"); }

F point_threads_key() {
  return integer("threads",
                 "Worker threads over the frequencies or speeds (0: all cores). Each point (for "
                 "campbell: each fixed chunk of speeds, started from one seeded basis) is solved "
                 "on its own, so the results are bit-identical for any count; 1 on the sparse "
                 "(UMFPACK, CHOLMOD) paths when the system BLAS is a sequential OpenBLAS (the "
                 "notes say so). Inside a sweep, whose points already run on threads, keep 1.")
      .def("1")
      .ge(0)
      .le(4096);
}

F gear_pair_name_key() {
  return reference("pair", Ref::GearPair, "The [[gear_pairs]] entry analysed.")
      .note("gear_pair: every pair; otherwise the model's only pair");
}

F mesh_model_key() {
  return choice("model", {"dynamic", "infinite_inertia"},
                "Mesh model: the dynamic one-DOF model along the line of action, or the "
                "algebraic limit of infinite inertias F_d = F_s k(t) / k_mean.")
      .def("\"dynamic\"");
}

F contact_loss_key() {
  return boolean("contact_loss",
                 "Teeth separate when the dynamic transmission error falls to zero (false: "
                 "the linear time-periodic mesh law for every deflection).")
      .def("true");
}

F gear_key() {
  return integer("gear", "The gear whose tooth load is analysed: 1 or 2 (N = its teeth).")
      .def("1")
      .ge(1)
      .le(2);
}

F window_shift_key() {
  return number("window_shift", kNoUnit,
                "Shift of the tooth-load window against the STE cycle start (the tooth "
                "entering contact), in tooth pitches of that gear.")
      .def("0.0")
      .ge(-3.0)
      .le(3.0);
}

F contact_ratio_key() {
  return number("contact_ratio", kNoUnit,
                "Contact ratio of the tooth-load window (the tooth carries load for this "
                "many pitches).")
      .ge(1.0)
      .le(3.0)
      .note("the pair's total contact ratio eps_gamma");
}

F nodal_diameters_key() {
  return F("nodal_diameters", FieldType::NumberArray,
           "Nodal diameters h whose engine orders k = h, N - h, ... are tabulated.")
      .ge(0)
      .increasing()
      .note("0 .. N / 2");
}

F orders_per_diameter_key() {
  return integer("orders_per_diameter",
                 "Engine orders per nodal diameter: 2 gives k = h and k = N - h, more add "
                 "N + h, 2 N - h, ...")
      .def("2")
      .ge(1)
      .le(20);
}

F min_prominence_db_key() {
  return number("min_prominence_db", kNoUnit,
                "Measured peaks at least this prominent [dB] are reported.")
      .def("6.0")
      .ge(0);
}

F forced_pair_key() {
  return reference("pair", Ref::GearPair,
                   "The [[gear_pairs]] entry whose tooth force (cyclic_forced_response: "
                   "computed as mesh_harmonics does) or mesh force (gear_forced_response: "
                   "the blocked force F_s k(t) / k_mean at the mesh orders) excites the "
                   "structure.")
      .note("force_amplitude");
}

F force_amplitude_key() {
  return F("force_amplitude", FieldType::NumberOrArray,
           "Harmonic force amplitude [N] without a gear pair: one value for every order, "
           "or one per entry of engine_orders (cyclic_forced_response) or per mesh order "
           "1 .. max_mesh_order (gear_forced_response), or F_k, F_2k, ... on harmonics "
           "1, 2, ... (damper_ring_response).")
      .unit(kNewton)
      .gt(0);
}

F harmonics_rpm_key() {
  return number("harmonics_rpm", kRpm,
                "Speed of gear 1 at which the dynamic mesh force, and so the tooth-force "
                "harmonics, are computed (model = \"dynamic\"); the harmonics are then used "
                "at every speed of the range.")
      .gt(0)
      .note("required with model = \"dynamic\"");
}

F force_direction_key() {
  return vector3("force_direction", kNoUnit,
                 "Direction of an explicit force_amplitude in global components of the "
                 "sector (the rotating frame), normalised.")
      .nonzero()
      .note("tangential, -e_theta at each excitation node");
}

F cone_apex_key() {
  return choice("cone_apex", {"minus_z", "plus_z"},
                "Side of the pitch-cone apex along the solid's z axis: the axial tooth "
                "force (positive away from the apex, gear/tooth_forces.hpp) points the "
                "other way.")
      .def("\"minus_z\"");
}

F excitation_set_key() {
  return text("excitation_set",
              "Node set of the sector carrying the tooth load (the load is shared equally "
              "by its nodes).")
      .def("\"excitation\"");
}

F sensor_sets_key() {
  return F("sensor_sets", FieldType::StringArray,
           "Node sets of the sector whose response is reported: one point per set, its "
           "node nearest to the set's centroid.")
      .def("[]")
      .unique();
}

F sensor_nodes_key() {
  return F("sensor_nodes", FieldType::NumberArray,
           "Node ids of the sector mesh whose response is reported.")
      .def("[]")
      .ge(0);
}

F sensor_components_key() {
  return F("sensor_components", FieldType::DofList,
           "Components reported at each sensor point, in the global axes of the sector "
           "(which turn with the gear: the rotating frame).")
      .def("[\"ux\", \"uy\", \"uz\"]")
      .choices(kComponentChoices);
}

F damping_ratio_key() {
  return number("damping_ratio", kNoUnit, "Modal damping ratio zeta of every mode.").gt(0).lt(1);
}

F q_factor_key() {
  return number("q_factor", kNoUnit, "Quality factor Q = 1 / (2 zeta) of every mode.").gt(0.5);
}

F measured_file_key() {
  return text("measured_file",
              "Measured response over speed (CSV, docs/input-files.md, displacement "
              "amplitude) overlaid on the computed one and compared peak by peak.")
      .note("no comparison");
}

F measured_sensor_key() {
  return text("measured_sensor",
              "Computed curve compared with the measurement: its sensor name (in a cyclic "
              "sector <set or node<id>>_<component>).")
      .note("the first sensor");
}

F scale_to_measured_key() {
  return boolean("scale_to_measured",
                 "Scale the harmonic force so that the computed peak matches the measured "
                 "one, and report the implied force.")
      .def("false");
}

std::vector<double> speed_range(const TableContext& t) {
  if (t.has("speed_rpm")) return t.at("speed_rpm").numbers;
  const double a = t.at("speed_start_rpm").number, b = t.at("speed_stop_rpm").number;
  if (b <= a)
    t.fail("speed_stop_rpm",
           fmt::format("a speed > speed_start_rpm = {} rpm (the range would be empty)",
                       value_text(a / kRpm.to_si)),
           fmt::format("{} rpm", value_text(b / kRpm.to_si)));
  return spaced(a, b, static_cast<int>(t.at("speed_count").integer), false);
}

std::vector<double> positive_speed_range(const TableContext& t, const std::string& why) {
  std::vector<double> speeds = speed_range(t);
  for (double w : speeds)
    if (!(w > 0.0))
      t.fail(t.has("speed_rpm") ? "speed_rpm" : "speed_start_rpm",
             fmt::format("speeds > 0 rpm ({})", why),
             fmt::format("{} rpm", value_text(w / kRpm.to_si)));
  return speeds;
}

void finish_tooth_excitation(CyclicForcedResponseSettings& s, const TableContext& t) {
  s.speeds = positive_speed_range(t, "the excitation frequency k W must be positive");
  const bool pair = t.has("pair");
  for (const char* key :
       {"gear", "model", "contact_loss", "window_shift", "contact_ratio", "harmonics_rpm"})
    if (t.has(key) && !pair)
      t.fail(key, "a `pair` whose tooth force it shapes (or leave it out with force_amplitude)",
             "no pair");
  if (t.has("force_direction") && pair)
    t.fail("force_direction",
           "no force_direction with a gear pair (its tooth forces set the direction)",
           "a direction");
  if (pair && s.model == MeshForceModel::Dynamic && !t.has("harmonics_rpm"))
    t.fail("harmonics_rpm",
           "the speed of gear 1 at which the dynamic mesh force is computed (model = "
           "\"dynamic\")",
           "nothing", "give harmonics_rpm, or use model = \"infinite_inertia\"");
  if (s.sensor_sets.empty() && s.sensor_nodes.empty())
    t.fail("sensor_sets", "at least one sensor point: sensor_sets or sensor_nodes", "neither");
}

model::Choice speed_range_choice(bool required) {
  return {{{"speed_rpm"}, {"speed_start_rpm", "speed_stop_rpm", "speed_count"}}, required, {}};
}

ReductionMethod reduction_method(const FieldValue& v) {
  constexpr ReductionMethod kMethods[] = {ReductionMethod::None, ReductionMethod::Guyan,
                                          ReductionMethod::CraigBampton};
  return kMethods[v.choice];
}

std::vector<int> integers_of(const FieldValue& v) {
  std::vector<int> out;
  for (double x : v.numbers) out.push_back(static_cast<int>(x));
  return out;
}

std::vector<double> amplitudes_of(const FieldValue& v) {
  return v.is_array ? v.numbers : std::vector<double>{v.number};
}

std::vector<model::Field> cyclic_sector_response_keys() {
  return {
      speed_list_key().read_by_finish<model::Analysis>(),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      n_modes_key().to_settings(&CyclicForcedResponseSettings::n_modes),
      solid_key().to_settings(&CyclicForcedResponseSettings::solid),
      reduction_key().to_settings_fn<CyclicForcedResponseSettings>(
          [](auto& s, const FieldValue& v) {
            s.reduction = v.given ? reduction_method(v) : ReductionMethod::None;
          }),
      reduced_modes_key().to_settings(&CyclicForcedResponseSettings::cb_modes),
      master_sets_key().to_settings(&CyclicForcedResponseSettings::master_sets),
      mesh_model_key().to_settings_enum(&CyclicForcedResponseSettings::model,
                                        {MeshForceModel::Dynamic, MeshForceModel::InfiniteInertia}),
      contact_loss_key().to_settings(&CyclicForcedResponseSettings::contact_loss),
      gear_key().to_settings(&CyclicForcedResponseSettings::gear),
      window_shift_key().to_settings(&CyclicForcedResponseSettings::window_shift),
      contact_ratio_key().to_settings(&CyclicForcedResponseSettings::contact_ratio),
      forced_pair_key().to_settings(&CyclicForcedResponseSettings::pair),
      force_amplitude_key().to_settings_fn<CyclicForcedResponseSettings>(
          [](auto& s, const FieldValue& v) { s.force_amplitude = amplitudes_of(v); }),
      harmonics_rpm_key().to_settings(&CyclicForcedResponseSettings::harmonics_speed),
      force_direction_key().to_settings(&CyclicForcedResponseSettings::force_direction),
      cone_apex_key().to_settings_fn<CyclicForcedResponseSettings>(
          [](auto& s, const FieldValue& v) { s.apex_below = v.choice == 0; }),
      excitation_set_key().to_settings(&CyclicForcedResponseSettings::excitation_set),
      sensor_sets_key().to_settings(&CyclicForcedResponseSettings::sensor_sets),
      sensor_nodes_key().to_settings_fn<CyclicForcedResponseSettings>(
          [](auto& s, const FieldValue& v) { s.sensor_nodes = integers_of(v); }),
      sensor_components_key().to_settings(&CyclicForcedResponseSettings::sensor_components),
      damping_ratio_key().to_settings(&CyclicForcedResponseSettings::damping_ratio),
      q_factor_key().to_settings(&CyclicForcedResponseSettings::q_factor),
  };
}

}  // namespace geardyn::analyses
