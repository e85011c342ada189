// The `type = "cyclic_forced_response"` analysis in the registry: its model-file keys and their
// rules, its checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/analyses/forced_helpers.hpp"
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
  auto& s = a.settings_of<CyclicForcedResponseSettings>();
  finish_tooth_excitation(s, t);
  if (t.has("force_amplitude")) {
    const FieldValue& v = t.at("force_amplitude");
    if (v.is_array && v.count != s.engine_orders.size())
      t.fail(
          "force_amplitude",
          s.engine_orders.empty()
              ? std::string("a single amplitude for every order (a list needs engine_orders "
                            "with one order per amplitude)")
              : fmt::format("{} amplitudes, one per engine_orders entry", s.engine_orders.size()),
          fmt::format("{} amplitudes", v.count));
  }
  if (t.has("engine_orders") && t.has("orders_per_diameter"))
    t.fail("orders_per_diameter", "no orders_per_diameter when engine_orders lists the orders",
           std::to_string(s.orders_per_diameter));
  for (const char* key : {"measured_sensor", "measured_engine_order", "scale_to_measured"})
    if (t.has(key) && !t.has("measured_file"))
      t.fail(key, "a measured_file to compare with", "no measured_file");
  if (s.measured_engine_order > 0 && !s.engine_orders.empty() &&
      std::find(s.engine_orders.begin(), s.engine_orders.end(), s.measured_engine_order) ==
          s.engine_orders.end())
    t.fail("measured_engine_order", "one of engine_orders (or 0: the superposed sum)",
           std::to_string(s.measured_engine_order));
  if (s.measured_engine_order == 0 && t.has("measured_file") && !s.superpose)
    t.fail("measured_engine_order",
           "the engine order compared with the measurement (the superposed sum needs superpose "
           "= true)",
           "0");
  if (s.reduction == ReductionMethod::Guyan)
    t.fail("reduction", "\"none\" or \"craig_bampton\" (the forced response sums modes)",
           "\"guyan\"");
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  check_cyclic_forced_response(a, path, check);
}

std::vector<model::Field> keys() {
  std::vector<model::Field> fields = cyclic_sector_response_keys();
  std::vector<model::Field> own = {
      nodal_diameters_key().to_settings_fn<CyclicForcedResponseSettings>(
          [](auto& s, const FieldValue& v) { s.nodal_diameters = integers_of(v); }),
      orders_per_diameter_key().to_settings(&CyclicForcedResponseSettings::orders_per_diameter),
      min_prominence_db_key().to_settings(&CyclicForcedResponseSettings::min_prominence_db),
      F("engine_orders", FieldType::NumberArray,
        "Engine orders k excited (each k = +-h mod sectors for a listed nodal "
        "diameter h).")
          .ge(1)
          .increasing()
          .note("orders_per_diameter orders per nodal diameter: h, N - h, ...")
          .to_settings_fn<CyclicForcedResponseSettings>(
              [](auto& s, const FieldValue& v) { s.engine_orders = integers_of(v); }),
      boolean("superpose",
              "Also report the superposition of all orders per sensor: the sum of "
              "amplitudes (upper bound of the peak) and the RMS.")
          .def("true")
          .to_settings(&CyclicForcedResponseSettings::superpose),
      measured_file_key().to_settings(&CyclicForcedResponseSettings::measured_file),
      measured_sensor_key().to_settings(&CyclicForcedResponseSettings::measured_sensor),
      integer("measured_engine_order",
              "Engine order of the computed curve compared with the measurement (0: the "
              "superposed sum of amplitudes).")
          .def("0")
          .ge(0)
          .le(100000)
          .to_settings(&CyclicForcedResponseSettings::measured_engine_order),
      scale_to_measured_key().to_settings(&CyclicForcedResponseSettings::scale_to_measured),
  };
  fields.insert(fields.end(), own.begin(), own.end());
  return fields;
}

}  // namespace

AnalysisType cyclic_forced_response_analysis() {
  AnalysisType type;
  type.name = "cyclic_forced_response";
  type.declare = [] {
    auto d = declaration<CyclicForcedResponseSettings>(
        "cyclic_forced_response",
        "Forced response of a cyclic solid (a gear) to the "
        "engine-order harmonics of its tooth force over speed, "
        "per nodal diameter and engine order (modal sum), the "
        "resonance table, the superposition of the orders, and "
        "the comparison with a measured response.");
    d.fields = keys();
    d.choices = {speed_range_choice(true),
                 {{{"pair"}, {"force_amplitude"}}, true, {}},
                 {{{"damping_ratio"}, {"q_factor"}}, true, {}}};
    d.finish = finish;
    d.check = check;
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_cyclic_forced_response_inputs(m, a.settings_of<CyclicForcedResponseSettings>(), c);
  };
  type.run = runner(run_cyclic_forced_response, cyclic_forced_response_output);
  type.scalars = {
      {"peak_amplitude",
       "",
       "Largest amplitude over speed at `sensor` (sum of the engine orders' amplitudes).",
       {"sensor"}},
      {"peak_location", "rpm", "Speed of that peak.", {"sensor"}},
      {"amplitude_at",
       "",
       "Amplitude at `sensor` at speed `at_rpm` (sum of the engine orders, linear "
       "interpolation).",
       {"sensor", "at_rpm"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) -> double {
    const auto& r = result_of<CyclicForcedResponseResult>(o);
    const std::size_t k = r.sensor_index(q.sensor);
    const Eigen::VectorXd& w = r.response.speeds;
    return speed_curve_scalar(std::vector<double>(w.data(), w.data() + w.size()), r.sum_curve(k), q,
                              r.response.sensors[k].component >= 3 ? "rad" : "m", unit);
  };
  return type;
}

}  // namespace geardyn::analyses
