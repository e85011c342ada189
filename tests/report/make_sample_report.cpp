// Writes a sample results folder (CSV tables, manifest.json, report.html) whose report holds every
// kind of plot geardyn draws: log-log receptances, a linear phase plot, a Campbell diagram with
// many traces (dashed backward whirl, dotted engine orders, markers with hover text), equal-aspect
// orbits, a long time history that the report thins, a heat map (contact pattern), and a failed
// and an incomplete analysis.
// The browser test (check_report.mjs) then opens the report in Chromium.
//
// Usage: make_sample_report OUTDIR      (prints the number of plots in the report)
#include <cmath>
#include <complex>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geardyn/core/run_info.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/io/results_writer.hpp"
#include "geardyn/io/sha256.hpp"
#include "geardyn/report/html_report.hpp"

namespace {

using namespace geardyn;
constexpr double kPi = 3.14159265358979323846;

std::vector<double> logspace(double a, double b, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = a * std::pow(b / a, static_cast<double>(i) / static_cast<double>(n - 1));
  return v;
}

// Receptance of three modes, H(f) = sum 1 / (k_r (1 - (f/f_r)^2 + 2 i zeta f/f_r)).
AnalysisOutput frf_analysis() {
  AnalysisOutput out;
  out.name = "frf";
  out.type = "harmonic";
  out.run_time_s = 0.84;
  out.notes = {"Modal superposition of 12 modes; residual flexibility of the higher modes added.",
               "Checked against the direct solve at 20 frequencies: largest difference 0.3 %."};
  const std::vector<double> f = logspace(1.0, 5000.0, 2000);
  const double fr[3] = {48.2, 310.0, 1275.0}, zeta[3] = {0.02, 0.015, 0.03};
  const double k[3] = {2e7, 8e7, 3e8};
  Table table;
  table.name = "receptance";
  table.title = "Receptance at the gear mesh";
  std::vector<double> amp11(f.size()), amp12(f.size()), phase11(f.size());
  Plot amplitude{
      "amplitude", "Receptance magnitude", "frequency [Hz]", "|H| [m/N]", true, true, false, {}};
  Plot phase{"phase", "Receptance phase", "frequency [Hz]", "phase [deg]", true, false, false, {}};
  Trace a11{"H11 drive point", f, {}, Trace::Mode::Lines, "", {}, {}, {}};
  Trace a12{"H12 transfer", f, {}, Trace::Mode::Lines, "dash", {}, {}, {}};
  Trace p11{"H11 drive point", f, {}, Trace::Mode::Lines, "", {}, {}, {}};
  for (std::size_t i = 0; i < f.size(); ++i) {
    std::complex<double> h11 = 0.0, h12 = 0.0;
    for (int r = 0; r < 3; ++r) {
      const double w = f[i] / fr[r];
      const std::complex<double> hr =
          1.0 / (k[r] * std::complex<double>(1 - w * w, 2 * zeta[r] * w));
      h11 += hr;
      h12 += (r == 1 ? -0.6 : 0.8) * hr;
    }
    amp11[i] = std::abs(h11);
    amp12[i] = std::abs(h12);
    phase11[i] = std::arg(h11) * 180.0 / kPi;
  }
  a11.y = amp11;
  a12.y = amp12;
  p11.y = phase11;
  amplitude.traces = {a11, a12};
  phase.traces = {p11};
  out.plots = {amplitude, phase};
  table.add("frequency_hz", "Hz", f);
  table.add("h11_m_per_n", "m/N", amp11);
  table.add("h12_m_per_n", "m/N", amp12);
  table.add("h11_phase_deg", "deg", phase11);
  out.tables.push_back(table);
  return out;
}

std::string fmt_mode(int m, int dir) {
  return "mode " + std::to_string(m + 1) + (dir ? " backward" : " forward");
}

// Campbell diagram: 8 forward and 8 backward whirl branches, engine orders 1x and 23x (mesh),
// critical speeds as markers with hover text.
AnalysisOutput campbell_analysis() {
  AnalysisOutput out;
  out.name = "campbell";
  out.type = "campbell";
  out.run_time_s = 3.2;
  out.notes = {"40 speeds from 0 to 12000 rpm; modes tracked by MAC > 0.9 between speeds."};
  Plot plot{"campbell", "Campbell diagram", "speed [rpm]", "frequency [Hz]", false, false, false,
            {}};
  std::vector<double> speed;
  for (int i = 0; i <= 40; ++i) speed.push_back(300.0 * i);
  Table crit;
  crit.name = "critical_speeds";
  crit.title = "Critical speeds";
  std::vector<double> crit_rpm, crit_hz;
  std::vector<std::string> crit_order, crit_mode;
  for (int m = 0; m < 8; ++m) {
    const double f0 = 40.0 + 95.0 * m + 8.0 * m * m;
    for (int dir = 0; dir < 2; ++dir) {
      Trace t{fmt_mode(m, dir), speed, {}, Trace::Mode::Lines, dir ? "dash" : "", {}, {}, {}};
      for (double s : speed)
        t.y.push_back(f0 * (1.0 + (dir ? -1.0 : 1.0) * 0.04 * (m + 1) * s / 12000.0));
      plot.traces.push_back(t);
    }
  }
  for (int order : {1, 23}) {
    Trace t{std::to_string(order) + "x",
            {0.0, 12000.0},
            {0.0, order * 200.0},
            Trace::Mode::Lines,
            "dot",
            {},
            {},
            {}};
    plot.traces.push_back(t);
  }
  Trace marks{"critical speeds", {}, {}, Trace::Mode::Markers, "", {}, {}, {}};
  for (int m = 0; m < 8; ++m) {
    // Forward branch f = f0 (1 + c s) meets the 1x line f = s / 60 at s = f0 / (1/60 - f0 c).
    const double f0 = 40.0 + 95.0 * m + 8.0 * m * m;
    const double c = 0.04 * (m + 1) / 12000.0;
    const double denominator = 1.0 / 60.0 - f0 * c;
    if (denominator <= 0.0) continue;
    const double rpm = f0 / denominator;
    if (rpm > 12000.0) continue;
    marks.x.push_back(rpm);
    marks.y.push_back(rpm / 60.0);
    marks.hover.push_back("mode " + std::to_string(m + 1) + " forward, 1x");
    crit_rpm.push_back(rpm);
    crit_hz.push_back(rpm / 60.0);
    crit_order.push_back("1x");
    crit_mode.push_back(std::to_string(m + 1) + "F");
  }
  plot.traces.push_back(marks);
  out.plots = {plot};
  crit.add("speed_rpm", "rpm", crit_rpm);
  crit.add("frequency_hz", "Hz", crit_hz);
  crit.add_text("order", crit_order);
  crit.add_text("mode", crit_mode);
  out.tables.push_back(crit);
  return out;
}

// Orbits at three bearings: ellipses of different size and tilt, equal axes.
AnalysisOutput orbit_analysis() {
  AnalysisOutput out;
  out.name = "unbalance_orbits";
  out.type = "harmonic";
  out.run_time_s = 0.12;
  Plot plot{"orbits", "Orbits at 9000 rpm", "y [µm]", "z [µm]", false, false, true, {}};
  const double a[3] = {12.0, 7.5, 20.0}, b[3] = {6.0, 7.0, 4.0}, tilt[3] = {0.3, 0.0, -0.8};
  for (int k = 0; k < 3; ++k) {
    Trace t{"bearing " + std::to_string(k + 1), {}, {}, Trace::Mode::Lines, "", {}, {}, {}};
    for (int i = 0; i <= 180; ++i) {
      const double phi = 2 * kPi * i / 180.0;
      const double u = a[k] * std::cos(phi), v = b[k] * std::sin(phi);
      t.x.push_back(u * std::cos(tilt[k]) - v * std::sin(tilt[k]));
      t.y.push_back(u * std::sin(tilt[k]) + v * std::cos(tilt[k]));
      t.hover.push_back("shaft angle " + std::to_string(2 * i) + "°");
    }
    plot.traces.push_back(t);
  }
  out.plots = {plot};
  Table t;
  t.name = "ellipses";
  t.title = "Orbit ellipses";
  t.add_text("bearing", {"bearing 1", "bearing 2", "bearing 3"});
  t.add("major_um", "µm", {12.0, 7.5, 20.0});
  t.add("minor_um", "µm", {6.0, 7.0, 4.0});
  out.tables.push_back(t);
  return out;
}

// A run-up time history of 120 001 samples: thinned in the report, whole in the CSV.
AnalysisOutput transient_analysis() {
  AnalysisOutput out;
  out.name = "run_up";
  out.type = "transient";
  out.run_time_s = 41.7;
  out.notes = {"Newmark average acceleration, dt = 25 µs; energy balance error 0.02 %."};
  const std::size_t n = 120001;
  Plot plot{"displacement", "Displacement at the gear, run-up",
            "time [s]",     "y [µm]",
            false,          false,
            false,          {}};
  Trace y{"y", {}, {}, Trace::Mode::Lines, "", {}, {}, {}};
  y.x.reserve(n);
  y.y.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 25e-6 * static_cast<double>(i);
    const double f = 10.0 + 60.0 * t;  // Hz, rising
    const double resonance = 1.0 + 6.0 * std::exp(-std::pow((f - 130.0) / 12.0, 2));
    y.x.push_back(t);
    y.y.push_back(resonance * std::sin(2 * kPi * (10.0 * t + 30.0 * t * t)));
  }
  plot.traces = {y};
  out.plots = {plot};
  Table table;
  table.name = "history";
  table.title = "Time history";
  table.add("time_s", "s", y.x);
  table.add("y_um", "µm", y.y);
  out.tables.push_back(table);
  return out;
}

// A contact pattern: the line load over face width x roll angle as a heat map (a crowned tooth:
// the load gathers at mid face), with blank (NaN) cells where the flank never meshes.
AnalysisOutput contact_pattern_analysis() {
  AnalysisOutput out;
  out.name = "contact_pattern";
  out.type = "tooth_contact";
  out.run_time_s = 0.05;
  Plot plot;
  plot.name = "line_load_map";
  plot.title = "Line load over the flank at 200 N m";
  plot.x_label = "face position [mm]";
  plot.y_label = "roll angle of gear 1 [deg]";
  Trace map;
  map.name = "200 N m";
  map.z_label = "line load [N/mm]";
  for (int k = 0; k < 40; ++k) map.x.push_back(0.5 + k);
  for (int i = 0; i < 30; ++i) map.y.push_back(12.0 + 0.5 * i);
  for (int i = 0; i < 30; ++i) {
    std::vector<double> row;
    for (int k = 0; k < 40; ++k) {
      const double z = (map.x[static_cast<std::size_t>(k)] - 20.0) / 20.0;
      row.push_back(i < 2 ? std::nan("") : 300.0 * (1.0 - z * z) * (1.0 + 0.3 * (i % 10 < 5)));
    }
    map.z.push_back(row);
  }
  plot.traces.push_back(map);
  out.plots = {plot};
  return out;
}

AnalysisOutput failed_analysis() {
  AnalysisOutput out;
  out.name = "mesh_harmonic";
  out.type = "harmonic";
  out.status = Status::Singular;
  out.run_time_s = 0.03;
  out.message =
      "dynamic stiffness K - w^2 M + i w C is singular at 0 rpm: the gear shaft has a free rigid "
      "body rotation.\nWhat usually helps: add a torsional spring to ground or a coupling to the "
      "drive shaft.";
  return out;
}

AnalysisOutput incomplete_analysis() {
  AnalysisOutput out;
  out.name = "modal";
  out.type = "modal";
  out.status = Status::FewerModes;
  out.run_time_s = 0.4;
  out.message = "asked for 20 modes below 5000 Hz, found 14 (the model has no more in that band)";
  out.notes = {"Eigen-equation residual below 1e-10 for every mode found."};
  Table t;
  t.name = "modes";
  t.title = "Natural frequencies";
  std::vector<double> mode, f, zeta;
  for (int i = 0; i < 14; ++i) {
    mode.push_back(i + 1);
    f.push_back(40.0 + 95.0 * (i / 2) + 8.0 * (i / 2) * (i / 2) + (i % 2) * 3.0);
    zeta.push_back(i == 5 ? std::nan("") : 0.01 + 0.002 * i);
  }
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("damping_ratio", "", zeta);
  out.tables.push_back(t);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path outdir = argv[1];
    const std::filesystem::path model = outdir.parent_path() / "sample_model.toml";
    std::filesystem::create_directories(outdir.parent_path().empty() ? "." : outdir.parent_path());
    std::ofstream(model) << "title = \"Sample geared rotor <report test>\"\n";

    RunInfo info;
    info.model_path = model;
    info.model_sha256 = io::sha256_file(model);
    info.command_line = "make_sample_report " + std::string(argv[1]);
    const std::vector<AnalysisOutput> outputs = {
        incomplete_analysis(),     campbell_analysis(),  frf_analysis(),
        orbit_analysis(),          transient_analysis(), failed_analysis(),
        contact_pattern_analysis()};
    std::size_t plots = 0;
    for (const auto& o : outputs) plots += o.plots.size();
    io::write_results(outdir, info, outputs, report::render_html(info, outputs));
    std::printf("%zu\n", plots);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_sample_report: %s\n", e.what());
    return 1;
  }
  return 0;
}
