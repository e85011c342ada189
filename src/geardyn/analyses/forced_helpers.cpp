#include "geardyn/analyses/forced_helpers.hpp"

#include "geardyn/analyses/cyclic_forced_response.hpp"  // the settings sector_excitation.hpp uses
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/sector_excitation.hpp"

namespace geardyn::analyses {

gear::MeasuredResponse read_measured(const model::Model& model, const std::string& name,
                                     const std::string& file) {
  gear::MeasuredResponse m =
      gear::read_measured_response_csv(analyses::resolve_model_path(model, file));
  if (m.abscissa != gear::ResponseAbscissa::SpeedRpm || m.amplitude_unit != "m")
    throw InputError(
        where_of(model, name), key_of(model, name, "measured_file"),
        "a measured displacement over speed: columns speed_rpm and amplitude_m "
        "(or _mm, _um, _nm), like the computed response",
        fmt::format("'{}' with {} and an amplitude in {}", m.source,
                    m.abscissa == gear::ResponseAbscissa::SpeedRpm ? "speed_rpm" : "frequency_hz",
                    m.amplitude_unit));
  return m;
}

Table force_scaling_table(const gear::PeakComparison& pc, const std::string& what,
                          const std::vector<std::pair<std::string, std::vector<double>>>& ids,
                          const std::vector<double>& used) {
  Table f;
  f.name = "force_scaling";
  f.title = fmt::format("{} that make the computed peak match the measured one (scale {:.6g})",
                        what, pc.measured.amplitude / pc.computed.amplitude);
  std::vector<double> implied, sc;
  for (double u : used) {
    const gear::ForceScaling fsc = gear::scale_force_to_peak(pc, u);
    implied.push_back(fsc.implied_force_n);
    sc.push_back(fsc.scale);
  }
  for (const auto& [column, values] : ids) f.add(column, "", values);
  f.add("force_used_n", "N", used);
  f.add("implied_force_n", "N", implied);
  f.add("scale", "", sc);
  return f;
}

MeasuredComparison compare_with_measured(AnalysisOutput& out, const gear::MeasuredResponse& m,
                                         const std::vector<double>& rpm,
                                         const std::vector<double>& computed,
                                         const std::string& curve_name, double min_prominence_db) {
  MeasuredComparison c;
  gear::CorrelationOptions co;
  co.min_prominence_db = min_prominence_db;
  c.peaks = gear::compare_peaks(m.x, m.amplitude, rpm, computed, co);
  c.plot.name = "measured_overlay";
  c.plot.title = fmt::format("Measured response ({}) and the computed {}", m.source, curve_name);
  c.plot.x_label = "speed [rpm]";
  c.plot.y_label = "amplitude [m]";
  c.plot.y_log = true;
  Trace mt = curve("measured", m.x, m.amplitude);
  mt.mode = Trace::Mode::Markers;
  c.plot.traces.push_back(std::move(mt));
  c.plot.traces.push_back(curve("computed", rpm, computed));
  if (c.peaks.empty()) {
    out.notes.push_back(fmt::format(
        "Measured file {}: no peak with a prominence of {:.3g} dB; nothing compared (lower "
        "min_prominence_db or measure across the resonance).",
        m.source, min_prominence_db));
    return c;
  }
  Table t = gear::correlation_table(c.peaks, gear::ResponseAbscissa::SpeedRpm, "m", "comparison");
  t.title = fmt::format(
      "Measured versus computed peaks ({}); mismatch = (computed - measured) / measured",
      curve_name);
  out.tables.push_back(std::move(t));
  for (std::size_t j = 1; j < c.peaks.size(); ++j)
    if (c.peaks[j].measured.amplitude > c.peaks[c.main].measured.amplitude) c.main = j;
  const gear::PeakComparison& pc = c.peaks[c.main];
  out.notes.push_back(
      fmt::format("Largest measured peak at {:.6g} rpm, {:.4g} m, Q = {:.4g}; computed {:.6g} rpm, "
                  "{:.4g} m, Q = {:.4g}: speed {:+.2f} %, amplitude {:+.1f} %, Q {:+.1f} %.",
                  pc.measured.x, pc.measured.amplitude, pc.measured.q_factor, pc.computed.x,
                  pc.computed.amplitude, pc.computed.q_factor, 100 * pc.x_mismatch,
                  100 * pc.amplitude_mismatch, 100 * pc.q_mismatch));
  return c;
}

}  // namespace geardyn::analyses
