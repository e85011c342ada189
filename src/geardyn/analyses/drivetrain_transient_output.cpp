// Tables, plots and notes of the drivetrain_transient analysis.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/analyses/drivetrain_transient.hpp"
#include "geardyn/analyses/plot_envelope.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::analyses {
namespace {

constexpr int kMinSpectrumSamples = 16;

std::vector<double> column(const Eigen::MatrixXd& m, std::size_t c) {
  const Eigen::VectorXd col = m.col(static_cast<Eigen::Index>(c));
  return {col.data(), col.data() + col.size()};
}

void add_static(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  if (r.static_rows_element.empty()) return;
  Table t;
  t.name = "static_equilibrium";
  t.title =
      fmt::format("Static equilibrium under load and preloads ({} iterations, |r| = {:.3g} N)",
                  r.equilibrium.iterations, r.equilibrium.residual);
  t.add_text("element", r.static_rows_element);
  t.add_text("quantity", r.static_rows_quantity);
  t.add("value", "", r.static_rows_value);
  t.add_text("unit", r.static_rows_unit);
  out.tables.push_back(std::move(t));
}

void add_eigen(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  if (!r.linearised) return;
  Table t;
  t.name = "eigen";
  t.title = "Linearised modes at the operating point (static equilibrium; ADAMS layout)";
  std::vector<double> mode, f, zeta, re, im;
  for (std::size_t k = 0; k < r.linearisation.modes.size(); ++k) {
    const drivetrain::LinearMode& m = r.linearisation.modes[k];
    mode.push_back(static_cast<double>(k + 1));
    f.push_back(m.natural_frequency_hz);
    zeta.push_back(m.damping_ratio);
    re.push_back(m.real_hz);
    im.push_back(m.imag_hz);
  }
  t.add("mode", "", mode);
  t.add("undamped_natural_frequency_hz", "Hz", f);
  t.add("damping_ratio", "", zeta);
  t.add("real_hz", "Hz", re);
  t.add("imaginary_hz", "Hz", im);
  out.tables.push_back(std::move(t));
}

void add_history(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  Table t;
  t.name = "time_history";
  t.title = "Time histories at the output sample rate";
  t.add("time_s", "s", r.time);
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    t.add(r.channels[c].name, r.channels[c].unit, column(r.values, c));
  out.tables.push_back(std::move(t));
  std::vector<std::string> groups;
  for (const auto& ch : r.channels)
    if (std::find(groups.begin(), groups.end(), ch.group) == groups.end())
      groups.push_back(ch.group);
  for (const std::string& g : groups) {
    Plot plot;
    plot.name = "time_" + g;
    plot.title = "Time histories: " + g;
    plot.x_label = "time [s]";
    for (std::size_t c = 0; c < r.channels.size(); ++c) {
      if (r.channels[c].group != g) continue;
      plot.y_label = g + " [" + r.channels[c].unit + "]";
      Trace tr;
      tr.name = r.channels[c].name;
      envelope(r.time, r.values.col(static_cast<Eigen::Index>(c)), tr.x, tr.y);
      plot.traces.push_back(std::move(tr));
    }
    out.plots.push_back(std::move(plot));
  }
}

void add_summary(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  Table t;
  t.name = "summary";
  t.title = "Peak and RMS of every channel over the record";
  std::vector<std::string> name, unit;
  std::vector<double> mn, mx, peak, rms, mean;
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const Eigen::VectorXd x = r.values.col(static_cast<Eigen::Index>(c));
    name.push_back(r.channels[c].name);
    unit.push_back(r.channels[c].unit);
    const bool any = x.size() > 0;
    mn.push_back(any ? x.minCoeff() : 0.0);
    mx.push_back(any ? x.maxCoeff() : 0.0);
    peak.push_back(any ? x.cwiseAbs().maxCoeff() : 0.0);
    rms.push_back(any ? std::sqrt(x.squaredNorm() / static_cast<double>(x.size())) : 0.0);
    mean.push_back(any ? x.mean() : 0.0);
  }
  t.add_text("channel", name);
  t.add_text("unit", unit);
  t.add("min", "", mn);
  t.add("max", "", mx);
  t.add("peak", "", peak);
  t.add("rms", "", rms);
  t.add("mean", "", mean);
  out.tables.push_back(std::move(t));
}

void add_spectra(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
                 AnalysisOutput& out) {
  const auto first = static_cast<Eigen::Index>(
      std::lower_bound(r.time.begin(), r.time.end(), s.spectrum_start - 1e-12) - r.time.begin());
  const Eigen::Index n = static_cast<Eigen::Index>(r.time.size()) - first;
  if (n < kMinSpectrumSamples) {
    out.notes.push_back(
        fmt::format("fewer than {} samples after spectrum_start: no spectra", kMinSpectrumSamples));
    return;
  }
  Table t;
  t.name = "spectrum";
  t.title = fmt::format("Amplitude spectra (0-peak, Hann) of t >= {:.6g} s", s.spectrum_start);
  Plot plot;
  plot.name = "spectrum";
  plot.title = "Amplitude spectra (0-peak, Hann): transmission error and accelerations";
  plot.x_label = "frequency [Hz]";
  plot.y_label = "amplitude (0-peak)";
  plot.y_log = true;
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const Eigen::VectorXd x = r.values.col(static_cast<Eigen::Index>(c)).segment(first, n);
    const signal::AmplitudeSpectrum sp = signal::amplitude_spectrum(x, s.sample_rate);
    if (c == 0)
      t.add("frequency_hz", "Hz",
            {sp.frequency_hz.data(), sp.frequency_hz.data() + sp.frequency_hz.size()});
    t.add(r.channels[c].name, r.channels[c].unit,
          {sp.amplitude.data(), sp.amplitude.data() + sp.amplitude.size()});
    if (r.channels[c].group == "dte" || r.channels[c].group == "acceleration") {
      Trace tr;
      tr.name = r.channels[c].name;
      const std::vector<double> f(sp.frequency_hz.data(),
                                  sp.frequency_hz.data() + sp.frequency_hz.size());
      envelope(f, sp.amplitude, tr.x, tr.y);
      plot.traces.push_back(std::move(tr));
    }
  }
  out.tables.push_back(std::move(t));
  if (!plot.traces.empty()) out.plots.push_back(std::move(plot));
}

void add_contacts(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  if (r.switch_names.empty()) return;
  Table t;
  t.name = "contacts";
  t.title = "Contact and joint states: fraction of the samples closed (switch function > 0)";
  t.add_text("switch", r.switch_names);
  t.add("closed_fraction", "", r.closed_fraction);
  out.tables.push_back(std::move(t));
  // A stop or a mesh's drive flank that never touches carried nothing: likely a modelling
  // error (gap, direction, nodes). Back flanks and bolts that never open are the normal case.
  auto matters = [](const std::string& s) {
    return s.rfind("contact '", 0) == 0 || s.find("' drive flank") != std::string::npos;
  };
  for (std::size_t k = 0; k < r.switch_names.size(); ++k)
    if (r.closed_fraction[k] == 0.0 && !r.time.empty() && matters(r.switch_names[k]))
      out.notes.push_back(fmt::format(
          "WARNING: {} never closed during the run: the contact carried no load (check its gap, "
          "backlash, direction and nodes)",
          r.switch_names[k]));
}

void add_integration(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  const transient::AdaptiveSummary& i = r.integration;
  Table t;
  t.name = "integration";
  t.title = "Integrator work";
  t.add_text("quantity",
             {"integrator", "linear solver", "steps", "rejected (error)", "rejected (Newton)",
              "Newton iterations", "factorisations", "residual evaluations", "events located",
              "smallest step [s]", "largest step [s]", "samples", "status"});
  t.add_text("value",
             {i.integrator, i.solver, std::to_string(i.steps), std::to_string(i.rejected_error),
              std::to_string(i.rejected_newton), std::to_string(i.newton_iterations),
              std::to_string(i.factorizations), std::to_string(i.residual_evaluations),
              std::to_string(i.events), fmt::format("{:.3g}", i.min_step_taken),
              fmt::format("{:.3g}", i.max_step_taken), std::to_string(i.samples),
              std::string(to_string(i.status))});
  out.tables.push_back(std::move(t));
}

}  // namespace

AnalysisOutput drivetrain_transient_output(const model::Model&,
                                           const DrivetrainTransientSettings& settings,
                                           const DrivetrainTransientResult& result,
                                           const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "drivetrain_transient";
  out.status = result.status;
  out.message = result.message;
  out.run_time_s = result.run_time_s;
  add_static(result, out);
  add_eigen(result, out);
  if (!result.time.empty()) {
    add_history(result, out);
    add_summary(result, out);
    add_spectra(settings, result, out);
  }
  add_contacts(result, out);
  add_integration(result, out);
  const transient::AdaptiveSummary& i = result.integration;
  out.notes.push_back(fmt::format(
      "{} integration to {:.6g} s: {} steps ({} rejected by the error test, {} by Newton), "
      "{} factorisations; local error tolerance rtol = {:g}, atol = {:g} m; samples at {:g} Hz "
      "interpolated within the steps",
      i.integrator, i.end_time, i.steps, i.rejected_error, i.rejected_newton, i.factorizations,
      settings.relative_tolerance, settings.absolute_tolerance, settings.sample_rate));
  if (result.linearised) {
    const auto& L = result.linearisation;
    out.notes.push_back(fmt::format(
        "linearisation at the static equilibrium: {} modes, {} rigid-body, largest backward "
        "error {:.2g}{}",
        L.modes.size(), L.rigid_body_modes, L.max_residual,
        L.unstable_modes > 0
            ? fmt::format("; UNSTABLE: {} mode(s) with negative damping", L.unstable_modes)
            : std::string()));
  }
  return out;
}

}  // namespace geardyn::analyses
