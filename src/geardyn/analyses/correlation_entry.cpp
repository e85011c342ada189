// The `type = "correlation"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/registry.hpp"
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

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<CorrelationResult>(o);
  if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.peaks.size())
    throw std::runtime_error(fmt::format("{}: peak mode = {} of a measured response with {} peak{}",
                                         q.quantity, q.mode, r.peaks.size(),
                                         r.peaks.size() == 1 ? "" : "s"));
  const gear::PeakEstimate& p = r.peaks[static_cast<std::size_t>(q.mode - 1)];
  const bool speed = r.measured.abscissa == gear::ResponseAbscissa::SpeedRpm;
  if (q.quantity == "measured_peak_location") {
    unit = speed ? "rpm" : "Hz";
    return p.x;
  }
  if (q.quantity == "measured_peak_amplitude") {
    unit = r.measured.amplitude_unit;
    return p.amplitude;
  }
  if (q.quantity == "measured_peak_q") {
    unit.clear();
    return p.q_factor;  // NaN when a half-power crossing lies outside the data
  }
  throw std::runtime_error(fmt::format("correlation offers no scalar \'{}\'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      text("measured_file",
           "Measured response CSV relative to the model file (format in "
           "docs/input-files.md: speed_rpm or frequency_hz, amplitude_<unit>, optional "
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
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_correlation_inputs(m, a.settings_of<CorrelationSettings>(), c);
  };
  type.run = runner(run_correlation, correlation_output);
  type.scalars = {
      {"measured_peak_location",
       "Hz",
       "Location of measured peak `mode` (peaks counted in order of location), in Hz or rpm as "
       "the measured file's abscissa.",
       {"mode"}},
      {"measured_peak_amplitude",
       "",
       "Amplitude of measured peak `mode`, in the measured file's SI unit.",
       {"mode"}},
      {"measured_peak_q",
       "",
       "Half-power quality factor Q of measured peak `mode` (NaN when a crossing lies outside "
       "the data).",
       {"mode"}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
