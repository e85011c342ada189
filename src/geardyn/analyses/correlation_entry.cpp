// The `type = "correlation"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/scalar_tables.hpp"
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
  auto& s = a.settings_of<CorrelationSettings>();
  s.reference_is_speed = !t.has("reference_peak_hz");
  const bool reference = t.has("reference_peak_rpm") || t.has("reference_peak_hz");
  for (const char* key : {"reference_amplitude", "reference_q"})
    if (t.has(key) && !reference)
      t.fail(key, "reference_peak_rpm or reference_peak_hz with it (where the reference peak is)",
             "no reference peak position");
}

std::vector<model::Field> keys() {
  return {
      text("measured_file",
           "Measured response CSV relative to the model file (format in "
           "gear/correlation.hpp: speed_rpm or frequency_hz, amplitude_<unit>, optional "
           "phase_deg).")
          .required()
          .to_settings(&CorrelationSettings::measured_file),
      min_prominence_db_key().to_settings(&CorrelationSettings::min_prominence_db),
      integer("max_peaks", "At most this many peaks (the most prominent).")
          .def("8")
          .ge(1)
          .le(1000)
          .to_settings(&CorrelationSettings::max_peaks),
      number("reference_peak_rpm", kRpm,
             "Position of a reference (e.g. computed) peak, for a measured file over "
             "speed; the nearest measured peak is compared with it.")
          .gt(0)
          .note("no comparison")
          .to_settings(&CorrelationSettings::reference_peak),
      number("reference_peak_hz", kHertz,
             "Position of a reference peak, for a measured file over frequency.")
          .gt(0)
          .note("no comparison")
          .to_settings(&CorrelationSettings::reference_peak),
      number("reference_amplitude", kNoUnit,
             "Amplitude of the reference peak, in the SI unit of the measured amplitude "
             "(m, m/s, m/s^2, N, strain or Pa).")
          .unit_note("SI unit of the measured amplitude")
          .gt(0)
          .note("no amplitude comparison")
          .to_settings(&CorrelationSettings::reference_amplitude),
      number("reference_q", kNoUnit, "Quality factor Q of the reference peak.")
          .gt(0)
          .note("no Q comparison")
          .to_settings(&CorrelationSettings::reference_q),
  };
}

}  // namespace

AnalysisType correlation_analysis() {
  AnalysisType type;
  type.name = "correlation";
  type.declare = [] {
    auto d =
        declaration<CorrelationSettings>("correlation",
                                         "Resonance peaks and Q (half-power) of a measured "
                                         "response, optionally compared with a reference peak.");
    d.fields = keys();
    d.choices = {{{{"reference_peak_rpm"}, {"reference_peak_hz"}}, false, {}}};
    d.finish = finish;
    return d;
  };
  type.run = [](const model::Model& m, const Analysis& a, const Context& c) {
    return Outcome{run_correlation(m, a.settings_of<CorrelationSettings>(), a.name, c.progress()),
                   nullptr};
  };
  return type;
}

}  // namespace geardyn::analyses
