// The `type = "unbalance"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
#include "geardyn/analyses/unbalance.hpp"
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
  a.settings_of<UnbalanceSettings>().speeds =
      positive_speed_range(t, "reverse rotation: negative speed ratios");
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
      point_threads_key().to_settings(&UnbalanceSettings::threads),
  };
}

constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

// The sensor's amplitude over speed as table "response" lists it: order after order, each over
// the speeds.
ResponseCurve response_curve(const UnbalanceResult& r, const std::string& sensor) {
  std::size_t s = 0;
  while (s < r.sensors.size() && r.sensors[s].name != sensor) ++s;
  if (s == r.sensors.size())
    throw std::runtime_error(fmt::format("no amplitude column for sensor '{}'", sensor));
  ResponseCurve c;
  for (std::size_t o = 0; o < r.orders.size(); ++o) {
    c.groups.emplace_back();
    for (std::size_t i = 0; i < r.speeds.size(); ++i) {
      c.groups.back().push_back(c.x.size());
      c.x.push_back(r.speeds[i] * kRpmPerRadS);
      c.amplitude.push_back(
          std::abs(r.response[o](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s))));
    }
  }
  c.x_unit = "rpm";
  c.amplitude_unit = r.sensors[s].rotational ? "rad" : "m";
  c.per_rad_s = 60.0 / units::kTwoPi;
  return c;
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
  type.run = runner(run_unbalance, unbalance_output);
  type.scalars = {
      {"peak_amplitude", "", "Largest response amplitude at `sensor`.", {"sensor"}},
      {"peak_location", "rpm", "Speed of that peak.", {"sensor"}},
      {"amplitude_at", "", "Amplitude at `sensor` at speed `at_rpm`.", {"sensor", "at_rpm"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) {
    return response_scalar(response_curve(result_of<UnbalanceResult>(o), q.sensor), q, unit);
  };
  return type;
}

}  // namespace geardyn::analyses
