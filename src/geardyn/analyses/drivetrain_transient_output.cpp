// Tables, plots and notes of the drivetrain_transient analysis.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "geardyn/analyses/drivetrain_transient.hpp"
#include "geardyn/analyses/plot_envelope.hpp"
#include "geardyn/io/time_history_h5.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::analyses {
namespace {

constexpr int kMinSpectrumSamples = 16;
/// Records of more values (samples x channels) go to time_history.h5 instead of a CSV table;
/// the spectrum table is cut to as many values.
constexpr double kMaxCsvValues = 2e6;

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

void add_mode_shapes(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  if (!r.linearised || r.shape_sensors.empty() || r.shape_at_sensors.rows() == 0) return;
  Table t;
  t.name = "mode_shapes";
  t.title = "Linearised mode shapes at the virtual sensors (1 at the largest sensor of each mode)";
  std::vector<double> mode, f;
  for (Eigen::Index k = 0; k < r.shape_at_sensors.rows(); ++k) {
    mode.push_back(static_cast<double>(k + 1));
    f.push_back(r.linearisation.modes[static_cast<std::size_t>(k)].natural_frequency_hz);
  }
  t.add("mode", "", mode);
  t.add("undamped_natural_frequency_hz", "Hz", f);
  for (std::size_t j = 0; j < r.shape_sensors.size(); ++j) {
    std::vector<double> amp, phase;
    for (Eigen::Index k = 0; k < r.shape_at_sensors.rows(); ++k) {
      const std::complex<double> z = r.shape_at_sensors(k, static_cast<Eigen::Index>(j));
      amp.push_back(std::abs(z));
      phase.push_back(std::arg(z) * 180.0 / M_PI);
    }
    t.add(r.shape_sensors[j] + "_amplitude", "", amp);
    t.add(r.shape_sensors[j] + "_phase_deg", "deg", phase);
  }
  out.tables.push_back(std::move(t));
}

void add_history(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
                 const Context& context, AnalysisOutput& out) {
  const double values = static_cast<double>(r.time.size()) * static_cast<double>(r.channels.size());
  if (values <= kMaxCsvValues) {
    Table t;
    t.name = "time_history";
    t.title = "Time histories at the output sample rate";
    t.add("time_s", "s", r.time);
    for (std::size_t c = 0; c < r.channels.size(); ++c)
      t.add(r.channels[c].name, r.channels[c].unit, column(r.values, c));
    out.tables.push_back(std::move(t));
  } else {
    // The writer calls this after the analysis returns: the record is copied into it.
    struct Record {
      std::vector<double> time;
      std::vector<io::TimeHistoryChannel> channels;
      Eigen::MatrixXd values;
    };
    auto rec = std::make_shared<Record>();
    rec->time = r.time;
    for (const auto& c : r.channels) rec->channels.push_back({c.name, c.unit});
    rec->values = r.values;
    const double rate = s.sample_rate();
    const std::string analysis = context.name();
    out.files.push_back(
        {"time_history.h5",
         fmt::format("time histories, {} samples x {} channels at {:g} Hz (HDF5: /time and "
                     "/channels/<name>, docs/output-reference.md)",
                     r.time.size(), r.channels.size(), rate),
         [rec, rate, analysis](const std::filesystem::path& path) {
           io::write_time_history_h5(path, rate, rec->time, rec->channels, rec->values,
                                     rec->time.size(), {{"analysis", analysis}});
         }});
    out.notes.push_back(fmt::format(
        "the record ({:.3g} values) is written to time_history.h5, not to a CSV table (more "
        "than {:.0e} values)",
        values, kMaxCsvValues));
  }
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

/// Orbit plots: one displacement sensor against another on the same node, over the samples at
/// t >= spectrum_start (the run's steady part when spectrum_start marks it), at most
/// kMaxOrbitPoints points (every k-th sample).
void add_orbits(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
                AnalysisOutput& out) {
  constexpr std::size_t kMaxOrbitPoints = 5000;
  const auto first = static_cast<std::size_t>(
      std::lower_bound(r.time.begin(), r.time.end(), s.spectrum_start - 1e-12) - r.time.begin());
  if (first >= r.time.size()) return;
  const std::size_t n = r.time.size() - first;
  const std::size_t stride = (n + kMaxOrbitPoints - 1) / kMaxOrbitPoints;
  for (const auto& [a, b] : r.orbits) {
    const DrivetrainChannel& ca = r.channels[a];
    const DrivetrainChannel& cb = r.channels[b];
    Plot plot;
    plot.name = "orbit_" + ca.name + "_" + cb.name;
    plot.title =
        fmt::format("Orbit: {} against {} (t >= {:.6g} s)", cb.name, ca.name, s.spectrum_start);
    plot.x_label = ca.name + " [" + ca.unit + "]";
    plot.y_label = cb.name + " [" + cb.unit + "]";
    plot.equal_aspect = true;
    Trace tr;
    tr.name = "orbit";
    for (std::size_t i = first; i < r.time.size(); i += stride) {
      tr.x.push_back(r.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a)));
      tr.y.push_back(r.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(b)));
    }
    plot.traces.push_back(std::move(tr));
    out.plots.push_back(std::move(plot));
  }
}

/// The FRF's notes: what was summed, the truncation at 0 Hz and against the direct solve.
void frf_notes(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
               AnalysisOutput& out) {
  const drivetrain::ModalFrf& F = r.frf;
  const double f_max = F.frequency_hz.back();
  out.notes.push_back(fmt::format(
      "FRF by modal superposition at the operating point (right and left eigenvectors of the "
      "linearised, non-symmetric pencil): {} modes up to {:.6g} Hz, each with its conjugate; "
      "unit {} '{}' over [{:.6g}, {:.6g}] Hz, {} points",
      F.modes_used, F.highest_mode_hz, r.frf_load_unit == "N" ? "force" : "moment",
      s.frf_excitation, F.frequency_hz.front(), f_max, F.frequency_hz.size()));
  if (F.static_checked)
    out.notes.push_back(fmt::format(
        "FRF residual flexibility (modal truncation): at 0 Hz the exact static receptance "
        "K_t^-1 f reaches {:.3g} {}/{} at the sensors, the modal sum {:.3g}, their largest "
        "difference {:.3g} ({:.2g} of the exact): the static part of the modes above {:.6g} Hz, "
        "{}",
        F.static_exact.cwiseAbs().maxCoeff(), r.frf_output_units.front(), r.frf_load_unit,
        F.static_modal.cwiseAbs().maxCoeff(),
        (F.static_modal - F.static_exact.cast<std::complex<double>>()).cwiseAbs().maxCoeff(),
        F.static_truncation, F.highest_mode_hz,
        F.static_corrected ? "added to the FRF at every frequency (frf_static_correction)"
                           : "which the FRF leaves out (frf_static_correction = false)"));
  else
    out.notes.push_back(
        "FRF residual flexibility not measured: K_t is singular at the operating point (a "
        "rigid-body or free spin), whose roots the sum leaves out");
  for (std::size_t i = 0; i < r.frf_check_hz.size(); ++i)
    out.notes.push_back(fmt::format(
        "FRF check against the direct solve (K_t - w^2 M + i w D)^-1 f at {:.6g} Hz: largest "
        "deviation {:.2g} of the largest sensor's value (the truncated modes' dynamic part)",
        r.frf_check_hz[i], r.frf_check_deviation[i]));
  if (f_max > F.highest_mode_hz)
    out.notes.push_back(fmt::format(
        "the FRF band reaches {:.6g} Hz, above the highest mode in the sum ({:.6g} Hz): there "
        "the truncated modes are missing; raise `modes` to cover the band",
        f_max, F.highest_mode_hz));
  if (r.linearisation.rigid_body_modes > 0)
    out.notes.push_back(
        fmt::format("the FRF leaves out {} rigid-body root(s) of the linearisation (a free spin)",
                    r.linearisation.rigid_body_modes));
}

/// Table and plot "frf": magnitude and phase of every sensor's response per unit load.
void add_frf(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
             AnalysisOutput& out) {
  if (!r.has_frf) return;
  const drivetrain::ModalFrf& F = r.frf;
  if (F.status != Status::Ok || F.frequency_hz.empty()) {
    out.notes.push_back("no FRF: " + F.message);
    return;
  }
  static const char* suffix[3] = {"", "_per_s", "_per_s2"};
  static const char* unit_suffix[3] = {"", "/s", "/s^2"};
  static const char* what[3] = {"receptance", "mobility", "accelerance"};
  const auto q = static_cast<std::size_t>(s.frf_quantity);
  const std::string load = r.frf_load_unit == "N" ? "n" : "nm";
  Table t;
  t.name = "frf";
  t.title = fmt::format(
      "FRF by modal superposition at the operating point: {} per unit {} '{}' "
      "({} modes)",
      what[q], r.frf_load_unit == "N" ? "force" : "moment", s.frf_excitation, F.modes_used);
  t.add("frequency_hz", "Hz", F.frequency_hz);
  Plot plot;
  plot.name = "frf";
  plot.title = fmt::format("FRF ({}) to '{}' by modal superposition; markers: linearised modes",
                           what[q], s.frf_excitation);
  plot.x_label = "frequency [Hz]";
  plot.y_label = fmt::format("|{}| [{}{}/{}]", what[q],
                             r.frf_output_units.empty() ? "m" : r.frf_output_units[0],
                             unit_suffix[q], r.frf_load_unit);
  plot.y_log = true;
  Eigen::MatrixXd magnitude(F.receptance.rows(), F.receptance.cols());
  for (Eigen::Index j = 0; j < F.receptance.cols(); ++j) {
    const std::string& u = r.frf_output_units[static_cast<std::size_t>(j)];
    std::vector<double> mag, phase;
    for (Eigen::Index i = 0; i < F.receptance.rows(); ++i) {
      const std::complex<double> iw(0.0, 2.0 * M_PI * F.frequency_hz[static_cast<std::size_t>(i)]);
      std::complex<double> h = F.receptance(i, j);
      for (std::size_t k = 0; k < q; ++k) h *= iw;
      mag.push_back(std::abs(h));
      phase.push_back(std::arg(h) * 180.0 / M_PI);
      magnitude(i, j) = mag.back();
    }
    const std::string& name = r.frf_outputs[static_cast<std::size_t>(j)];
    t.add(fmt::format("{}_{}{}_per_{}", name, u, suffix[q], load),
          u + unit_suffix[q] + "/" + r.frf_load_unit, mag);
    t.add(name + "_phase_deg", "deg", phase);
    Trace tr;
    tr.name = name;
    tr.x = F.frequency_hz;
    tr.y = std::move(mag);
    plot.traces.push_back(std::move(tr));
  }
  // The modes in the band, marked at the largest sensor's magnitude at the nearest point.
  Trace marks;
  marks.name = "modes";
  marks.mode = Trace::Mode::Markers;
  const double df = F.frequency_hz.size() > 1 ? F.frequency_hz[1] - F.frequency_hz[0] : 1.0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(F.modes_used); ++k) {
    const drivetrain::LinearMode& m = r.linearisation.modes[k];
    const double f = m.natural_frequency_hz;
    if (f < F.frequency_hz.front() || f > F.frequency_hz.back() || magnitude.cols() == 0) continue;
    const auto i = static_cast<Eigen::Index>(std::lround((f - F.frequency_hz.front()) / df));
    marks.x.push_back(f);
    marks.y.push_back(magnitude.row(std::min(i, magnitude.rows() - 1)).maxCoeff());
    marks.hover.push_back(
        fmt::format("mode {}: {:.6g} Hz, damping ratio {:.3g}", k + 1, f, m.damping_ratio));
  }
  if (!marks.x.empty()) plot.traces.push_back(std::move(marks));
  out.tables.push_back(std::move(t));
  if (magnitude.cols() > 0) out.plots.push_back(std::move(plot));
  frf_notes(s, r, out);
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
  // Spectra of the vibration channels (transmission error, accelerations, forces, torques);
  // displacements, angles and speeds of a run-up are dominated by the rigid motion.
  std::vector<std::size_t> chosen;
  for (std::size_t c = 0; c < r.channels.size(); ++c) {
    const std::string& g = r.channels[c].group;
    if (g == "dte" || g == "acceleration" || g == "force" || g == "torque") chosen.push_back(c);
  }
  if (chosen.empty()) return;
  // The table keeps at most kMaxCsvValues values: the lowest bins when the record is long.
  const auto bins_all = static_cast<std::size_t>(n / 2 + 1);
  const std::size_t bins = std::min(
      bins_all, static_cast<std::size_t>(kMaxCsvValues / static_cast<double>(chosen.size() + 1)));
  Table t;
  t.name = "spectrum";
  t.title = fmt::format("Amplitude spectra (0-peak, Hann) of t >= {:.6g} s", s.spectrum_start);
  Plot plot;
  plot.name = "spectrum";
  plot.title = "Amplitude spectra (0-peak, Hann): transmission error and accelerations";
  plot.x_label = "frequency [Hz]";
  plot.y_label = "amplitude (0-peak)";
  plot.y_log = true;
  for (std::size_t c : chosen) {
    const Eigen::VectorXd x = r.values.col(static_cast<Eigen::Index>(c)).segment(first, n);
    const signal::AmplitudeSpectrum sp = signal::amplitude_spectrum(x, s.sample_rate());
    const auto keep = static_cast<Eigen::Index>(bins);
    if (!t.has_column("frequency_hz"))
      t.add("frequency_hz", "Hz", {sp.frequency_hz.data(), sp.frequency_hz.data() + keep});
    t.add(r.channels[c].name, r.channels[c].unit,
          {sp.amplitude.data(), sp.amplitude.data() + keep});
    if (r.channels[c].group == "dte" || r.channels[c].group == "acceleration") {
      Trace tr;
      tr.name = r.channels[c].name;
      const std::vector<double> f(sp.frequency_hz.data(), sp.frequency_hz.data() + keep);
      envelope(f, sp.amplitude.head(keep), tr.x, tr.y);
      plot.traces.push_back(std::move(tr));
    }
  }
  if (bins < bins_all)
    out.notes.push_back(fmt::format(
        "spectrum table: the lowest {} of {} frequency bins (up to {:.6g} Hz) to stay within "
        "{:.0e} values",
        bins, bins_all, static_cast<double>(bins - 1) * s.sample_rate() / static_cast<double>(n),
        kMaxCsvValues));
  out.tables.push_back(std::move(t));
  if (!plot.traces.empty()) out.plots.push_back(std::move(plot));
}

/// Amplitude of the order-`order` component of x in the angle theta (x ~ c + a cos(order theta)
/// + b sin(order theta), least squares) over samples [i0, i1).
double order_amplitude(const Eigen::VectorXd& theta, const Eigen::VectorXd& x, Eigen::Index i0,
                       Eigen::Index i1, double order) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (Eigen::Index i = i0; i < i1; ++i) {
    const Eigen::Vector3d phi(1.0, std::cos(order * theta[i]), std::sin(order * theta[i]));
    A += phi * phi.transpose();
    b += phi * x[i];
  }
  const Eigen::Vector3d c = A.ldlt().solve(b);
  return std::hypot(c[1], c[2]);
}

/// Table "orders": per mesh, the DTE's amplitude at mesh orders 1-3 (k z1 per revolution of
/// gear 1), fitted in gear 1's actual angle (so the orders stay sharp while the speed changes)
/// over successive windows of at least 8 mesh periods and 64 samples (at most 400 windows).
void add_orders(const DrivetrainTransientResult& r, AnalysisOutput& out) {
  const auto n = static_cast<Eigen::Index>(r.time.size());
  if (r.mesh_orders.empty() || n < 64) return;
  Plot plot;
  plot.name = "orders";
  plot.title = "Dynamic transmission error at the mesh orders over speed";
  plot.x_label = "gear 1 speed [rpm]";
  plot.y_label = "DTE (0-peak) [m]";
  plot.y_log = true;
  for (const DrivetrainMeshOrders& m : r.mesh_orders) {
    const Eigen::VectorXd theta = r.values.col(static_cast<Eigen::Index>(m.angle_channel));
    const Eigen::VectorXd x = r.values.col(static_cast<Eigen::Index>(m.dte_channel));
    const double periods = std::abs(theta[n - 1] - theta[0]) * m.teeth1 / (2.0 * M_PI);
    const double per_window = std::max(8.0, periods / 400.0);
    Table t;
    t.name = "orders_" + m.mesh;
    t.title = fmt::format(
        "Dynamic transmission error of mesh '{}' at its mesh orders (0-peak, fitted in gear 1's "
        "angle over windows of >= {:.3g} mesh periods)",
        m.mesh, per_window);
    std::vector<double> time, rpm;
    std::vector<std::vector<double>> amp(3);
    for (Eigen::Index i0 = 0; i0 < n;) {
      Eigen::Index i1 = i0 + 64;
      while (i1 < n && std::abs(theta[i1 - 1] - theta[i0]) * m.teeth1 / (2.0 * M_PI) < per_window)
        ++i1;
      if (i1 > n || std::abs(theta[i1 - 1] - theta[i0]) * m.teeth1 / (2.0 * M_PI) < per_window)
        break;
      const double t0 = r.time[static_cast<std::size_t>(i0)];
      const double t1 = r.time[static_cast<std::size_t>(i1 - 1)];
      time.push_back(0.5 * (t0 + t1));
      rpm.push_back((theta[i1 - 1] - theta[i0]) / (t1 - t0) * 60.0 / (2.0 * M_PI));
      for (int k = 0; k < 3; ++k)
        amp[static_cast<std::size_t>(k)].push_back(
            order_amplitude(theta, x, i0, i1, (k + 1.0) * m.teeth1));
      i0 = i1;
    }
    if (time.empty()) {
      out.notes.push_back(
          fmt::format("mesh '{}' turned through fewer than {:.3g} mesh periods: no order table",
                      m.mesh, per_window));
      continue;
    }
    t.add("time_s", "s", time);
    t.add("pinion_speed_rpm", "rpm", rpm);
    for (int k = 0; k < 3; ++k) {
      t.add(fmt::format("order{}_dte_m", k + 1), "m", amp[static_cast<std::size_t>(k)]);
      Trace tr;
      tr.name = fmt::format("{} mesh order {}", m.mesh, k + 1);
      tr.x = rpm;
      tr.y = amp[static_cast<std::size_t>(k)];
      plot.traces.push_back(std::move(tr));
    }
    out.tables.push_back(std::move(t));
  }
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

// The order analysis of the record (order_channels): the shared order_analysis core on the
// uniformly sampled samples from the one after which the reference angle keeps increasing (the
// shaft turns). A record too short for its blocks gets a note, not an error: the run is done.
void add_record_orders(const DrivetrainTransientSettings& s, const DrivetrainTransientResult& r,
                       const Context& context, AnalysisOutput& out) {
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < r.channels.size(); ++c)
      if (r.channels[c].name == name) return static_cast<Eigen::Index>(c);
    return Eigen::Index{-1};
  };
  auto n = static_cast<Eigen::Index>(r.time.size());
  if (n < 4) return;
  const double dt = r.time[1] - r.time[0];
  for (Eigen::Index j = 2; j < n; ++j)
    if (std::abs(r.time[static_cast<std::size_t>(j)] - r.time[static_cast<std::size_t>(j - 1)] -
                 dt) > 1e-6 * dt) {
      n = j;  // a last, shorter step: not on the sample grid
      break;
    }
  const Eigen::VectorXd t = Eigen::Map<const Eigen::VectorXd>(r.time.data(), n);
  const Eigen::VectorXd angle = r.values.col(column(s.order_reference)).head(n);
  Eigen::Index first = n - 1;
  while (first > 0 && angle[first] > angle[first - 1]) --first;
  Eigen::MatrixXd values(n, static_cast<Eigen::Index>(s.order_channels.size()));
  for (std::size_t c = 0; c < s.order_channels.size(); ++c)
    values.col(static_cast<Eigen::Index>(c)) = r.values.col(column(s.order_channels[c])).head(n);
  try {
    const OrderAnalysisResult orders =
        analyse_orders(t, values, s.order_channels, angle, first, n - 1, s.order_options, context);
    add_order_analysis_output(out, orders, s.order_options, "");
    std::string names;
    for (const std::string& c : s.order_channels) names += (names.empty() ? "" : ", ") + c;
    out.notes.push_back(fmt::format(
        "Order analysis of {} against the angle channel {} from t = {:.4g} s (the shaft turning "
        "from there on), as the analysis order_analysis.",
        names, s.order_reference, t[first]));
  } catch (const std::exception& e) {
    out.notes.push_back(fmt::format(
        "Order analysis not done: {} (order_revolutions_per_block, order_block_length).",
        e.what()));
  }
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
  add_mode_shapes(result, out);
  add_frf(settings, result, out);
  if (!result.time.empty()) {
    add_history(settings, result, context, out);
    add_orbits(settings, result, out);
    add_summary(result, out);
    add_spectra(settings, result, out);
    add_orders(result, out);
    if (!settings.order_channels.empty()) add_record_orders(settings, result, context, out);
  }
  add_contacts(result, out);
  add_integration(result, out);
  const transient::AdaptiveSummary& i = result.integration;
  out.notes.push_back(fmt::format(
      "{} integration to {:.6g} s: {} steps ({} rejected by the error test, {} by Newton), "
      "{} factorisations; local error tolerance rtol = {:g}, atol = {:g} m; samples at {:g} Hz "
      "interpolated within the steps",
      i.integrator, i.end_time, i.steps, i.rejected_error, i.rejected_newton, i.factorizations,
      settings.relative_tolerance, settings.absolute_tolerance, settings.sample_rate()));
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
