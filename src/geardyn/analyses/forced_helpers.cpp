#include "geardyn/analyses/forced_helpers.hpp"

#include <algorithm>
#include <cmath>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::analyses {

gear::MeasuredResponse read_measured(const model::Model& model, const Context& context,
                                     const std::string& file) {
  gear::MeasuredResponse m =
      gear::read_measured_response_csv(analyses::resolve_model_path(model, file));
  if (m.abscissa != gear::ResponseAbscissa::SpeedRpm || m.amplitude_unit != "m")
    throw context.error(
        "measured_file",
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

std::vector<gear::PeakComparison> measured_peaks(const gear::MeasuredResponse& m,
                                                 const std::vector<double>& rpm,
                                                 const std::vector<double>& computed,
                                                 double min_prominence_db) {
  gear::CorrelationOptions co;
  co.min_prominence_db = min_prominence_db;
  return gear::compare_peaks(m.x, m.amplitude, rpm, computed, co);
}

std::size_t largest_measured_peak(const std::vector<gear::PeakComparison>& peaks) {
  std::size_t main = 0;
  for (std::size_t j = 1; j < peaks.size(); ++j)
    if (peaks[j].measured.amplitude > peaks[main].measured.amplitude) main = j;
  return main;
}

MeasuredComparison compare_with_measured(AnalysisOutput& out, const gear::MeasuredResponse& m,
                                         const std::vector<double>& rpm,
                                         const std::vector<double>& computed,
                                         const std::string& curve_name, double min_prominence_db) {
  MeasuredComparison c;
  c.peaks = measured_peaks(m, rpm, computed, min_prominence_db);
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
  c.main = largest_measured_peak(c.peaks);
  const gear::PeakComparison& pc = c.peaks[c.main];
  out.notes.push_back(
      fmt::format("Largest measured peak at {:.6g} rpm, {:.4g} m, Q = {:.4g}; computed {:.6g} rpm, "
                  "{:.4g} m, Q = {:.4g}: speed {:+.2f} %, amplitude {:+.1f} %, Q {:+.1f} %.",
                  pc.measured.x, pc.measured.amplitude, pc.measured.q_factor, pc.computed.x,
                  pc.computed.amplitude, pc.computed.q_factor, 100 * pc.x_mismatch,
                  100 * pc.amplitude_mismatch, 100 * pc.q_mismatch));
  return c;
}

std::size_t largest_sample(const std::vector<double>& a) {
  if (a.empty()) throw std::runtime_error("the response curve has no sample");
  return static_cast<std::size_t>(std::max_element(a.begin(), a.end()) - a.begin());
}

double value_at(const std::vector<double>& x, const std::vector<double>& a, double at,
                double per_unit, const std::string& unit) {
  const double u = at;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (std::abs(x[k] - u) <= 1e-9 * std::max(1.0, std::abs(u))) return a[k];
    if (k + 1 < x.size() && (x[k] - u) * (x[k + 1] - u) < 0.0) {
      const double s = (u - x[k]) / (x[k + 1] - x[k]);
      return (1.0 - s) * a[k] + s * a[k + 1];
    }
  }
  throw std::runtime_error(
      fmt::format("{:.6g} {} is outside the analysis range", at * per_unit, unit));
}

double speed_curve_scalar(const std::vector<double>& speeds, const std::vector<double>& amplitude,
                          const ScalarRequest& q, const std::string& curve_unit,
                          std::string& unit) {
  unit = curve_unit;
  if (q.quantity == "peak_amplitude") return amplitude[largest_sample(amplitude)];
  if (q.quantity == "peak_location") {
    unit = "rpm";
    return units::rad_per_s_to_rpm(speeds[largest_sample(amplitude)]);
  }
  if (q.quantity == "amplitude_at")
    return value_at(speeds, amplitude, q.at, units::rad_per_s_to_rpm(1.0), "rpm");
  throw std::logic_error("a forced response over speed offers no scalar " + q.quantity);
}

}  // namespace geardyn::analyses
