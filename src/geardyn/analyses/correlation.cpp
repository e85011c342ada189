#include "geardyn/analyses/correlation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/analyses/gear_common.hpp"  // MeshForceModel, which pair_model.hpp uses
#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

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

}  // namespace

AnalysisOutput run_correlation(const model::Model& model, const CorrelationSettings& settings,
                               const std::string& name, Progress& progress) {
  const gear::MeasuredResponse m =
      gear::read_measured_response_csv(resolve_model_path(model, settings.measured_file));
  const bool speed = m.abscissa == gear::ResponseAbscissa::SpeedRpm;
  const std::string xs = speed ? "speed_rpm" : "frequency_hz";
  const std::string xu = speed ? "rpm" : "Hz";
  const std::string as = "amplitude_" + amplitude_suffix(m.amplitude_unit);

  progress.start("correlation", 1);
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
  progress.update(1);
  progress.finish();
  if (found.empty())
    throw NumericalError(
        name, fmt::format("no resonance peak with a prominence of at least {:.3g} dB in {}; lower "
                          "min_prominence_db or measure across the resonance",
                          settings.min_prominence_db, m.source));

  std::vector<gear::PeakEstimate> peaks;
  for (const signal::PeakIndex& p : found)
    peaks.push_back(gear::estimate_peak(m.x, m.amplitude, m.x[p.index]));

  AnalysisOutput out;
  {
    Table t;
    t.name = "peaks";
    t.title = fmt::format("Resonance peaks of the measured response {} (half-power Q)", m.source);
    std::vector<double> index, x, a, x1, x2, q, zeta, band, prominence;
    for (std::size_t i = 0; i < peaks.size(); ++i) {
      const gear::PeakEstimate& p = peaks[i];
      index.push_back(static_cast<double>(i + 1));
      x.push_back(p.x);
      a.push_back(p.amplitude);
      x1.push_back(p.x1);
      x2.push_back(p.x2);
      q.push_back(p.q_factor);
      zeta.push_back(p.damping_ratio);
      band.push_back(p.points_in_band);
      prominence.push_back(found[i].prominence);
    }
    t.add("peak", "", index);
    t.add(xs, xu, x);
    t.add(as, m.amplitude_unit, a);
    t.add("half_power_low_" + xs, xu, x1);
    t.add("half_power_high_" + xs, xu, x2);
    t.add("q_factor", "", q);
    t.add("damping_ratio", "", zeta);
    t.add("points_in_band", "", band);
    t.add("prominence_db", "dB", prominence);
    out.tables.push_back(std::move(t));
  }
  {
    Plot p;
    p.name = "measured";
    p.title = "Measured response and its resonance peaks";
    p.x_label = speed ? "speed [rpm]" : "frequency [Hz]";
    p.y_label = fmt::format("amplitude [{}]", m.amplitude_unit);
    p.traces.push_back(line("measured", m.x, m.amplitude, Trace::Mode::LinesMarkers));
    std::vector<double> px, py, hx, hy;
    for (const gear::PeakEstimate& e : peaks) {
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
    out.plots.push_back(std::move(p));
  }
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const gear::PeakEstimate& p = peaks[i];
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

  if (!std::isnan(settings.reference_peak)) {
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
    Table t = gear::correlation_table({c}, m.abscissa, m.amplitude_unit, "comparison");
    t.title =
        "Measured peak versus the reference (computed) peak; mismatch = (reference - "
        "measured) / measured";
    out.tables.push_back(std::move(t));
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

}  // namespace geardyn::analyses
