#include "geardyn/analyses/correlation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <vector>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;

std::string amplitude_suffix(const std::string& si_unit) {
  std::string out;
  for (char c : si_unit) {
    if (c == '/')
      out += '_';
    else if (c != '^')
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

/// The peaks in the one peak-table layout (core/peak_table.hpp), with their prominence appended
/// as the last column. Q and the damping ratio are given when both half-power crossings lie in
/// the data (`resolved`); a peak with fewer than 3 samples in its band gets a note instead.
Table peaks_table(const CorrelationResult& r) {
  const gear::MeasuredResponse& m = r.measured;
  const bool speed = m.abscissa == gear::ResponseAbscissa::SpeedRpm;
  std::vector<PeakRow> rows;
  for (const gear::PeakEstimate& p : r.peaks) {
    PeakRow row;
    row.sensor = "measured";
    row.curve = "amplitude_" + amplitude_suffix(m.amplitude_unit);
    row.location = p.x;
    row.amplitude = p.amplitude;
    row.amplitude_unit = m.amplitude_unit;
    row.half_power_low = p.x1;
    row.half_power_high = p.x2;
    row.q_factor = p.q_factor;
    row.points_in_band = p.points_in_band;
    row.resolved = !std::isnan(p.q_factor);
    rows.push_back(std::move(row));
  }
  Table t = peak_table(
      "peaks", fmt::format("Resonance peaks of the measured response {} (half-power Q)", m.source),
      speed ? speed_axis() : frequency_axis(), rows);
  t.add("prominence_db", "dB", r.prominence_db);
  return t;
}

Plot measured_plot(const CorrelationResult& r) {
  const gear::MeasuredResponse& m = r.measured;
  Plot p;
  p.name = "measured";
  p.title = "Measured response and its resonance peaks";
  p.x_label = m.abscissa == gear::ResponseAbscissa::SpeedRpm ? "speed [rpm]" : "frequency [Hz]";
  p.y_label = fmt::format("amplitude [{}]", m.amplitude_unit);
  p.traces.push_back(line("measured", m.x, m.amplitude, Trace::Mode::LinesMarkers));
  std::vector<double> px, py, hx, hy;
  for (const gear::PeakEstimate& e : r.peaks) {
    px.push_back(e.x);
    py.push_back(e.amplitude);
    for (double xb : {e.x1, e.x2}) {
      if (std::isnan(xb)) continue;
      hx.push_back(xb);
      hy.push_back(e.amplitude / std::sqrt(2.0));
    }
  }
  p.traces.push_back(line("peak", px, py, Trace::Mode::Markers));
  if (!hx.empty()) p.traces.push_back(line("half-power points", hx, hy, Trace::Mode::Markers));
  return p;
}

/// The most prominent peaks of the measured curve (at most max_peaks), in order of location.
std::vector<signal::PeakIndex> prominent_peaks(const gear::MeasuredResponse& m,
                                               const CorrelationSettings& settings) {
  // Prominence in dB, so that a peak counts by its ratio to the curve around it.
  const double a_max = *std::max_element(m.amplitude.begin(), m.amplitude.end());
  std::vector<double> db(m.amplitude.size());
  for (std::size_t i = 0; i < db.size(); ++i)
    db[i] = 20.0 * std::log10(std::max(m.amplitude[i], 1e-12 * a_max));
  std::vector<signal::PeakIndex> found = a_max > 0.0
                                             ? signal::find_peaks(db, settings.min_prominence_db)
                                             : std::vector<signal::PeakIndex>{};
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.prominence > b.prominence; });
  if (found.size() > static_cast<std::size_t>(settings.max_peaks))
    found.resize(static_cast<std::size_t>(settings.max_peaks));
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.index < b.index; });
  return found;
}

/// The measured peak nearest the reference peak, compared with it.
gear::PeakComparison compare_with_reference(const CorrelationResult& r,
                                            const CorrelationSettings& settings) {
  const bool speed = r.measured.abscissa == gear::ResponseAbscissa::SpeedRpm;
  const std::vector<gear::PeakEstimate>& peaks = r.peaks;
  const double ref_x = speed ? to_rpm(settings.reference_peak) : settings.reference_peak / kTwoPi;
  std::size_t best = 0;
  for (std::size_t i = 1; i < peaks.size(); ++i)
    if (std::abs(peaks[i].x - ref_x) < std::abs(peaks[best].x - ref_x)) best = i;
  gear::PeakComparison c;
  c.measured = peaks[best];
  c.computed.x = ref_x;
  c.computed.amplitude = settings.reference_amplitude;
  c.computed.q_factor = settings.reference_q;
  c.x_mismatch = (ref_x - c.measured.x) / c.measured.x;
  c.amplitude_mismatch =
      (settings.reference_amplitude - c.measured.amplitude) / c.measured.amplitude;
  c.q_mismatch = (settings.reference_q - c.measured.q_factor) / c.measured.q_factor;
  return c;
}

}  // namespace

CorrelationResult run_correlation(const model::Model& model, const CorrelationSettings& settings,
                                  const Context& context) {
  CorrelationResult r;
  r.measured = gear::read_measured_response_csv(resolve_model_path(model, settings.measured_file));
  const gear::MeasuredResponse& m = r.measured;
  Progress& progress = context.progress();
  progress.start("correlation", 1);
  const std::vector<signal::PeakIndex> found = prominent_peaks(m, settings);
  progress.update(1);
  progress.finish();
  if (found.empty())
    throw NumericalError(
        context.name(),
        fmt::format("no resonance peak with a prominence of at least {:.3g} dB in {}; lower "
                    "min_prominence_db or measure across the resonance",
                    settings.min_prominence_db, m.source));
  for (const signal::PeakIndex& p : found) {
    r.peaks.push_back(gear::estimate_peak(m.x, m.amplitude, m.x[p.index]));
    r.prominence_db.push_back(p.prominence);
  }
  if (!std::isnan(settings.reference_peak)) r.comparison = compare_with_reference(r, settings);
  return r;
}

AnalysisOutput correlation_output(const model::Model& /*model*/,
                                  const CorrelationSettings& settings,
                                  const CorrelationResult& result, const Context& /*context*/) {
  const gear::MeasuredResponse& m = result.measured;
  const bool speed = m.abscissa == gear::ResponseAbscissa::SpeedRpm;
  const std::string xu = speed ? "rpm" : "Hz";
  AnalysisOutput out;
  out.tables.push_back(peaks_table(result));
  out.plots.push_back(measured_plot(result));
  for (std::size_t i = 0; i < result.peaks.size(); ++i) {
    const gear::PeakEstimate& p = result.peaks[i];
    if (std::isnan(p.q_factor))
      out.notes.push_back(fmt::format(
          "Peak {} at {:.6g} {}: a half-power crossing lies outside the data, so Q is not "
          "given; measure further on both sides of the peak.",
          i + 1, p.x, xu));
    else if (p.points_in_band < 3)
      out.notes.push_back(fmt::format(
          "Peak {} at {:.6g} {}: only {} samples inside the half-power band, so Q = {:.4g} is "
          "poorly resolved; measure with a finer {} step there.",
          i + 1, p.x, xu, p.points_in_band, p.q_factor, speed ? "speed" : "frequency"));
  }
  out.notes.push_back(
      "Q = x_peak / (x2 - x1) with the half-power (A / sqrt 2) crossings interpolated linearly "
      "between samples and the peak refined by a parabola (Ewins, Modal Testing, 4.3). Over "
      "speed, Q of an engine-order resonance equals the modal Q when the order is fixed.");

  if (result.comparison) {
    const gear::PeakComparison& c = *result.comparison;
    Table t = gear::correlation_table({c}, m.abscissa, m.amplitude_unit, "comparison");
    t.title =
        "Measured peak versus the reference (computed) peak; mismatch = (reference - "
        "measured) / measured";
    out.tables.push_back(std::move(t));
    // "thesis": A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears
    // Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018.
    if (!std::isnan(settings.reference_amplitude))
      out.notes.push_back(fmt::format(
          "Amplitude ratio measured / reference = {:.6g}: for a linear model, the harmonic "
          "excitation that reproduces the measured peak is the one used for the reference times "
          "this factor (thesis sec. 5.2).",
          c.measured.amplitude / settings.reference_amplitude));
  }
  out.notes.push_back(
      "Comparison with a response computed by another analysis of the same run is not wired "
      "yet: give its peak as reference_peak_rpm / reference_peak_hz, reference_amplitude and "
      "reference_q.");
  return out;
}

void check_correlation_inputs(const model::Model& model, const CorrelationSettings& c,
                              const Context& context) {
  namespace fs = std::filesystem;
  const fs::path path = resolve_model_path(model, c.measured_file);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw context.error("measured_file",
                        "a readable measured-response CSV file (relative to the model file)",
                        fmt::format("\"{}\" ({} does not exist)", c.measured_file, path.string()));
  const gear::MeasuredResponse m = gear::read_measured_response_csv(path);
  if (!std::isnan(c.reference_peak)) {
    const bool file_speed = m.abscissa == gear::ResponseAbscissa::SpeedRpm;
    if (file_speed != c.reference_is_speed)
      throw context.error(
          c.reference_is_speed ? "reference_peak_rpm" : "reference_peak_hz",
          fmt::format("reference_peak_{} for a measured file over {}", file_speed ? "rpm" : "hz",
                      file_speed ? "speed_rpm" : "frequency_hz"),
          fmt::format("reference_peak_{}", c.reference_is_speed ? "rpm" : "hz"));
  }
}

}  // namespace geardyn::analyses
