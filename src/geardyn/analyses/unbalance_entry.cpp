// The `type = "unbalance"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/scalar_tables.hpp"
#include "geardyn/analyses/unbalance.hpp"
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
  a.settings_of<UnbalanceSettings>().speeds = speed_range(t);
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& u = a.settings_of<UnbalanceSettings>();
  const auto& m = check.model();
  check.check_named(path + ".unbalances", u.unbalances, model::names_of(m.unbalances), "unbalance",
                    "unbalances");
  check.check_named(path + ".sensors", u.sensors, model::names_of(m.sensors), "sensor", "sensors");
  if (m.unbalances.empty())
    check.fail(path + ".type", "an analysis type whose excitation exists in the model",
               "\"unbalance\", but the model has no [[unbalances]]");
}

std::vector<model::Field> keys() {
  return {
      speed_list_key().to_settings(&UnbalanceSettings::speeds),
      speed_start_rpm_key().read_by_finish<model::Analysis>(),
      speed_stop_rpm_key().read_by_finish<model::Analysis>(),
      speed_count_key().read_by_finish<model::Analysis>(),
      unbalances_key().to_settings(&UnbalanceSettings::unbalances),
      sensors_key().to_settings(&UnbalanceSettings::sensors),
  };
}

}  // namespace

AnalysisType unbalance_analysis() {
  AnalysisType type;
  type.name = "unbalance";
  type.declare = [] {
    auto d = declaration<UnbalanceSettings>("unbalance", "Steady unbalance response versus speed.");
    d.fields = keys();
    d.choices = {speed_range_choice(true)};
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.run = [](const model::Model& m, const Analysis& a, const Context& c) {
    const auto& s = a.settings_of<UnbalanceSettings>();
    UnbalanceResult r = run_unbalance(m, c.system(), s, c.progress());
    AnalysisOutput out = unbalance_output(m, c.system(), r, a.name);
    return outcome(std::move(out), std::move(r));
  };
  type.scalars = {
      {"peak_amplitude", "", "Largest response amplitude at `sensor`.", {"sensor"}},
      {"peak_location", "rpm", "Speed of that peak.", {"sensor"}},
      {"amplitude_at", "", "Amplitude at `sensor` at speed `at_rpm`.", {"sensor", "at_rpm"}}};
  type.scalar = scalar_from_tables;
  return type;
}

}  // namespace geardyn::analyses
