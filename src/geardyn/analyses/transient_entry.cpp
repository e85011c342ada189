// The `type = "transient"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
#include "geardyn/analyses/transient.hpp"
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
  auto& s = a.settings_of<TransientSettings>();
  if (s.time_step >= s.duration)
    t.fail("time_step", fmt::format("a time step < duration = {} s", value_text(s.duration)),
           fmt::format("{} s", value_text(s.time_step)));
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& t = a.settings_of<TransientSettings>();
  const auto& m = check.model();
  check.check_named(path + ".unbalances", t.unbalances, model::names_of(m.unbalances), "unbalance",
                    "unbalances");
  check.check_named(path + ".sensors", t.sensors, model::names_of(m.sensors), "sensor", "sensors");
  // The cost, before anything runs: steps and the size of the time history.
  const int n_sensors = static_cast<int>(t.sensors.empty() ? m.sensors.size() : t.sensors.size());
  if (const TransientCost cost = estimate_cost(t, n_sensors); !cost.excess().empty())
    check.fail(path + (cost.steps > TransientCost::kMaxSteps ? ".time_step" : ".output_every"),
               cost.excess(),
               fmt::format("duration = {:g} s, time_step = {:g} s, output_every = {}: {}",
                           t.duration, t.time_step, t.output_every, cost.describe()),
               "raise time_step or output_every, or shorten duration");
}

std::vector<model::Field> keys() {
  return {
      reference_speed_key().to_settings(&TransientSettings::speed),
      unbalances_key().to_settings(&TransientSettings::unbalances),
      sensors_key().to_settings(&TransientSettings::sensors),
      number("speed_end_rpm", kRpm, "End speed of a linear run-up over `duration`.")
          .ge(0)
          .note("constant speed")
          .to_settings(&TransientSettings::speed_end),
      number("duration", kSecond, "Simulated time.")
          .required()
          .gt(0)
          .to_settings(&TransientSettings::duration),
      number("time_step", kSecond, "Time step (< duration).")
          .required()
          .gt(0)
          .to_settings(&TransientSettings::time_step),
      choice("integrator", {"newmark", "generalized_alpha"},
             "Time integrator: Newmark average acceleration, or generalised-alpha with "
             "numerical damping set by rho_infinity.")
          .def("\"generalized_alpha\"")
          .to_settings_enum(&TransientSettings::integrator,
                            {Integrator::Newmark, Integrator::GeneralizedAlpha}),
      number("rho_infinity", kNoUnit,
             "Spectral radius at infinite frequency "
             "(generalised-alpha; 1: no numerical damping).")
          .def("0.9")
          .ge(0)
          .le(1)
          .to_settings(&TransientSettings::rho_infinity),
      number("steady_fraction", kNoUnit, "Last fraction of the record used for spectra and orbits.")
          .def("0.5")
          .gt(0)
          .le(1)
          .to_settings(&TransientSettings::steady_fraction),
      integer("output_every", "Store every n-th time step.")
          .def("1")
          .ge(1)
          .le(1000000)
          .to_settings(&TransientSettings::output_every),
  };
}

}  // namespace

AnalysisType transient_analysis() {
  AnalysisType type;
  type.name = "transient";
  type.declare = [] {
    auto d = declaration<TransientSettings>("transient",
                                            "Time integration at constant speed or in a linear "
                                            "run-up.");
    d.fields = keys();
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.run = runner(run_transient, transient_output);
  type.scalars = {
      {"max_response", "", "Largest |x(t)| of `sensor` over the record.", {"sensor"}},
      {"max_response_speed",
       "rpm",
       "Reference speed at that largest |x(t)| (in a run-up: where it passes resonance).",
       {"sensor"}},
      {"rms_response", "", "RMS of `sensor` over the steady part of the record.", {"sensor"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) {
    const TransientSensorSummary s = summarize_sensor(result_of<TransientResult>(o), q.sensor);
    if (q.quantity == "max_response") {
      unit = s.unit;
      return s.peak;
    }
    if (q.quantity == "max_response_speed") {
      unit = "rpm";
      return s.peak_speed * (60.0 / units::kTwoPi);
    }
    if (q.quantity == "rms_response") {
      unit = s.unit;
      return s.steady_rms;
    }
    unknown_scalar("transient", q.quantity);
  };
  return type;
}

}  // namespace geardyn::analyses
