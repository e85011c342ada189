// The `type = "gear_forced_response"` analysis in the registry: its model-file keys and their
// rules, its checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/gear_forced_response.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<GearForcedResponseSettings>();
  s.speeds = positive_speed_range(t, "the mesh frequency must be positive");
  for (const char* key : {"measured_sensor", "measured_mesh_order", "scale_to_measured"})
    if (t.has(key) && !t.has("measured_file"))
      t.fail(key, "a measured_file to compare with", "no measured_file");
  if (t.has("force_amplitude") && t.at("force_amplitude").is_array) {
    const std::size_t n = t.at("force_amplitude").count;
    if (!t.has("max_mesh_order"))
      s.max_mesh_order = static_cast<int>(n);
    else if (n != static_cast<std::size_t>(s.max_mesh_order))
      t.fail("force_amplitude",
             fmt::format("{} amplitudes, one per mesh order 1 .. max_mesh_order", s.max_mesh_order),
             fmt::format("{} amplitudes", n));
  }
  if (s.measured_mesh_order > s.max_mesh_order)
    t.fail("measured_mesh_order",
           fmt::format("a mesh order 1 .. max_mesh_order = {} (or 0: the sum)", s.max_mesh_order),
           std::to_string(s.measured_mesh_order));
}

// A gear mesh with teeth, the pair (if any) with the same teeth, sensors.
void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& g = a.settings_of<GearForcedResponseSettings>();
  if (!g.pair.empty()) {
    GearPairUse use;
    use.pair = &g.pair;
    check_gear_pair_use(a, path, check, use);
  }
  check_mesh_excitation(path, check, "gear_forced_response", g.gear_mesh, g.pair, g.sensors);
}

std::vector<model::Field> keys() {
  return {
      speed_list_key().read_by_finish<model::Analysis>(),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      n_modes_key().to_settings(&GearForcedResponseSettings::n_modes),
      sensors_key().to_settings(&GearForcedResponseSettings::sensors),
      min_prominence_db_key().to_settings(&GearForcedResponseSettings::min_prominence_db),
      forced_pair_key().to_settings(&GearForcedResponseSettings::pair),
      force_amplitude_key().to_settings_fn<GearForcedResponseSettings>(
          [](auto& s, const FieldValue& v) { s.force_amplitude = amplitudes_of(v); }),
      measured_file_key().to_settings(&GearForcedResponseSettings::measured_file),
      measured_sensor_key().to_settings(&GearForcedResponseSettings::measured_sensor),
      scale_to_measured_key().to_settings(&GearForcedResponseSettings::scale_to_measured),
      integer("measured_mesh_order",
              "Mesh order of the computed curve compared with the measurement (0: the "
              "sum of the amplitudes of all mesh orders).")
          .def("0")
          .ge(0)
          .le(100000)
          .to_settings(&GearForcedResponseSettings::measured_mesh_order),
      excited_gear_mesh_key().to_settings(&GearForcedResponseSettings::gear_mesh),
      max_mesh_order_key().to_settings(&GearForcedResponseSettings::max_mesh_order),
      residual_vectors_key().to_settings(&GearForcedResponseSettings::residual_vectors),
  };
}

}  // namespace

AnalysisType gear_forced_response_analysis() {
  AnalysisType type;
  type.name = "gear_forced_response";
  type.declare = [] {
    auto d = declaration<GearForcedResponseSettings>(
        "gear_forced_response",
        "Forced response of the rotor to the mesh-order "
        "harmonics of one gear mesh over speed (modal basis), "
        "with the resonance peaks and their Q.");
    d.fields = keys();
    d.choices = {speed_range_choice(true), {{{"pair"}, {"force_amplitude"}}, true, {}}};
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_gear_forced_response_inputs(m, a.settings_of<GearForcedResponseSettings>(), c);
  };
  type.run = runner(run_gear_forced_response, gear_forced_response_output);
  type.scalars = {
      {"peak_amplitude",
       "",
       "Largest amplitude over speed at `sensor` (sum of the mesh orders' amplitudes).",
       {"sensor"}},
      {"peak_location", "rpm", "Speed of that peak.", {"sensor"}},
      {"amplitude_at",
       "",
       "Amplitude at `sensor` at speed `at_rpm` (sum of the mesh orders, linear interpolation).",
       {"sensor", "at_rpm"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) -> double {
    const auto& r = result_of<GearForcedResponseResult>(o);
    const std::size_t k = r.sensor_index(q.sensor);
    const Eigen::VectorXd& w = r.response.speeds;
    const auto a = r.response.amplitude_sum.col(static_cast<Eigen::Index>(k));
    return speed_curve_scalar(std::vector<double>(w.data(), w.data() + w.size()),
                              std::vector<double>(a.data(), a.data() + a.size()), q,
                              r.response.sensors[k].rotational ? "rad" : "m", unit);
  };
  return type;
}

}  // namespace geardyn::analyses
