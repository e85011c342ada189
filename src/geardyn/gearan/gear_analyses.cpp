#include "geardyn/gearan/gear_analyses.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/gearan/tooth_force.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::gearan {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDeg = 180.0 / std::numbers::pi;

double to_rpm(double omega) { return omega * 60.0 / kTwoPi; }

/// Mesh frequency [Hz] at gear 1's speed `omega1` [rad/s]: f_m = z1 omega1 / 2 pi.
double mesh_frequency(double omega1, int teeth1) { return teeth1 * omega1 / kTwoPi; }

std::string rpm_text(double rpm) { return fmt::format("{:.6g} rpm", rpm); }

std::vector<double> scaled(const std::vector<double>& v, double factor) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * factor;
  return out;
}

Trace line(std::string name, std::vector<double> x, std::vector<double> y,
           Trace::Mode mode = Trace::Mode::Lines, std::string dash = {}) {
  Trace t;
  t.name = std::move(name);
  t.x = std::move(x);
  t.y = std::move(y);
  t.mode = mode;
  t.dash = std::move(dash);
  return t;
}

/// The STE the dynamic model uses, with the mesh stiffness it implies, over one mesh cycle.
Table ste_table(const PairModel& pm, const std::string& table_name) {
  const gear::SteCurve& ste = *pm.ste;
  const std::size_t n = ste.size();
  const double pitch = kTwoPi / pm.pair->teeth1;
  Table t;
  t.name = table_name;
  t.title = fmt::format(
      "Static transmission error and mesh stiffness of '{}' over one mesh cycle "
      "({}; sample 0: a tooth pair enters contact)",
      pm.pair->name, pm.ste_from_file ? "from " + pm.pair->ste_file : "synthetic, ISO 6336");
  std::vector<double> u(n), angle(n), e(n), eg(n), k(n);
  for (std::size_t j = 0; j < n; ++j) {
    u[j] = static_cast<double>(j) / static_cast<double>(n);
    angle[j] = u[j] * pitch * kDeg;
    e[j] = ste.ste_m()[j];
    eg[j] = ste.geometric_te_m()[j];
    k[j] = pm.static_force_n / (e[j] - eg[j]);
  }
  t.add("mesh_fraction", "", u);
  t.add("pinion_angle_deg", "deg", angle);
  t.add("ste_m", "m", e);
  t.add("ste_rad", "rad", scaled(e, 1.0 / pm.base_radius1_m));
  t.add("geometric_te_m", "m", eg);
  t.add("stiffness_n_per_m", "N/m", k);
  return t;
}

Table iso_table(const std::vector<PairModel>& pairs) {
  Table t;
  t.name = "iso_stiffness";
  t.title = "ISO 6336-1:2019 Method B tooth stiffness (per unit face width in N/(mm um))";
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols(16);
  for (const PairModel& pm : pairs) {
    const gear::IsoStiffness& s = pm.stiffness.iso;
    names.push_back(pm.pair->name);
    const double v[] = {s.normal_virtual_teeth_pinion,
                        s.normal_virtual_teeth_wheel,
                        s.flexibility_q_prime,
                        s.theoretical_single_stiffness,
                        s.correction_factor,
                        s.blank_factor,
                        s.basic_rack_factor,
                        s.helix_factor,
                        s.material_factor,
                        s.load_factor,
                        s.single_stiffness,
                        s.mesh_stiffness_alpha,
                        s.mesh_stiffness_beta,
                        s.single_stiffness_n_per_m,
                        s.mesh_stiffness_n_per_m,
                        pm.stiffness.mean_stiffness_n_per_m};
    for (std::size_t c = 0; c < cols.size(); ++c) cols[c].push_back(v[c]);
  }
  t.add_text("pair", names);
  const char* col_names[] = {"normal_virtual_teeth1",
                             "normal_virtual_teeth2",
                             "flexibility_q_prime_mm_um_per_n",
                             "theoretical_single_stiffness_n_per_mm_um",
                             "correction_factor_cm",
                             "blank_factor_cr",
                             "basic_rack_factor_cb",
                             "helix_factor",
                             "material_factor",
                             "load_factor",
                             "single_stiffness_n_per_mm_um",
                             "mesh_stiffness_alpha_n_per_mm_um",
                             "mesh_stiffness_beta_n_per_mm_um",
                             "single_stiffness_n_per_m",
                             "mesh_stiffness_n_per_m",
                             "curve_mean_stiffness_n_per_m"};
  const char* units[] = {"", "", "mm um/N",   "N/(mm um)", "",          "",    "",    "",
                         "", "", "N/(mm um)", "N/(mm um)", "N/(mm um)", "N/m", "N/m", "N/m"};
  for (std::size_t c = 0; c < cols.size(); ++c) t.add(col_names[c], units[c], cols[c]);
  return t;
}

/// Natural frequency of the mesh, sqrt(k_mean / m_e) / 2 pi [Hz], with k_mean of the STE used.
double mesh_natural_frequency_hz(const PairModel& pm, double mass_kg) {
  return std::sqrt(pm.static_force_n * pm.ste->mean_inverse_elastic_per_m() / mass_kg) / kTwoPi;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// gear_pair

AnalysisOutput run_gear_pair(const model::Model& model, const model::GearPairSettings& settings,
                             const std::string& name, Progress& progress) {
  (void)name;
  std::vector<PairModel> pairs;
  if (settings.pair.empty()) {
    for (std::size_t i = 0; i < model.gear_pairs.size(); ++i)
      pairs.push_back(build_pair_model(model, i));
  } else {
    pairs.push_back(build_pair_model(model, pair_index(model, settings.pair)));
  }
  progress.start("gear pairs", pairs.size());
  AnalysisOutput out;
  std::vector<gear::GearPairGeometry> geometries, force_pairs;
  std::vector<gear::MeshLoadCase> loads;
  for (const PairModel& pm : pairs) {
    geometries.push_back(pm.geometry);
    force_pairs.push_back(pm.geometry);
    force_pairs.push_back(pm.geometry);
    loads.push_back(pm.drive);
    loads.push_back(pm.coast);
  }
  out.tables.push_back(gear::geometry_table(geometries));
  out.tables.push_back(gear::tooth_force_table(force_pairs, loads));
  out.tables.push_back(iso_table(pairs));

  std::size_t done = 0;
  for (const PairModel& pm : pairs) {
    const std::string suffix = pairs.size() == 1 ? "" : "_" + pm.pair->name;
    Table ste = ste_table(pm, "mesh_stiffness" + suffix);
    const std::vector<double>& angle = ste.column("pinion_angle_deg").numbers;

    Plot k;
    k.name = "mesh_stiffness" + suffix;
    k.title = fmt::format("Mesh stiffness of '{}' over one mesh cycle", pm.pair->name);
    k.x_label = "rotation of gear 1 [deg]";
    k.y_label = "mesh stiffness [N/m]";
    k.traces.push_back(line(pm.ste_from_file ? "from the STE file" : "ISO 6336 (synthetic STE)",
                            angle, ste.column("stiffness_n_per_m").numbers));
    if (pm.ste_from_file) {
      // The ISO-based curve for comparison (unshifted: its sample 0 is the contact entry).
      std::vector<double> iso_angle = scaled(pm.stiffness.pinion_angle_rad, kDeg);
      k.traces.push_back(line("ISO 6336-1 (geometry)", iso_angle, pm.stiffness.stiffness_n_per_m,
                              Trace::Mode::Lines, "dash"));
    }
    Plot e;
    e.name = "ste" + suffix;
    e.title = fmt::format("Static transmission error of '{}' at T1 = {:.6g} N m", pm.pair->name,
                          pm.pair->torque);
    e.x_label = "rotation of gear 1 [deg]";
    e.y_label = "STE along the line of action [um]";
    e.traces.push_back(line("STE", angle, scaled(ste.column("ste_m").numbers, 1e6)));
    out.tables.push_back(std::move(ste));
    out.plots.push_back(std::move(k));
    out.plots.push_back(std::move(e));

    const gear::GearPairGeometry& g = pm.geometry;
    const double k_mean = pm.static_force_n * pm.ste->mean_inverse_elastic_per_m();
    out.notes.push_back(fmt::format(
        "'{}': contact ratio eps_alpha = {:.4f}, eps_beta = {:.4f}, eps_gamma = {:.4f}; mesh "
        "frequency = {} x speed of gear 1; F_s = T1 / r_b1 = {:.6g} N (r_b1 = {:.6g} m).",
        pm.pair->name, g.transverse_contact_ratio, g.overlap_ratio, g.total_contact_ratio,
        pm.pair->teeth1, pm.static_force_n, pm.base_radius1_m));
    out.notes.push_back(fmt::format(
        "'{}': mean mesh stiffness {:.6g} N/m from the {} (ISO 6336-1 c_gamma_alpha b = {:.6g} "
        "N/m); the time-varying ISO curve is a single-pair law with load sharing, not a "
        "loaded tooth-contact analysis.",
        pm.pair->name, k_mean,
        pm.ste_from_file ? fmt::format("STE file {}", pm.pair->ste_file)
                         : std::string("synthetic STE"),
        pm.stiffness.iso.mesh_stiffness_n_per_m));
    if (gear::is_bevel(g.spec.type))
      out.notes.push_back(fmt::format(
          "'{}': bevel / hypoid geometry as the virtual cylindrical pair at mid face (ISO "
          "10300-1, Tredgold); the ISO 6336 stiffness is applied to that virtual pair, outside "
          "ISO 6336's scope.",
          pm.pair->name));
    if (!std::isnan(pm.pair->inertia1) && !std::isnan(pm.pair->inertia2)) {
      const double fn = mesh_natural_frequency_hz(pm, pm.equivalent_mass_kg());
      out.notes.push_back(fmt::format(
          "'{}': mesh natural frequency sqrt(k_mean / m_e) / 2 pi = {:.6g} Hz (m_e = {:.6g} kg), "
          "met by the mesh frequency at gear 1 speed {}.",
          pm.pair->name, fn, pm.equivalent_mass_kg(), rpm_text(60.0 * fn / pm.pair->teeth1)));
    }
    progress.update(++done);
  }
  progress.finish();
  return out;
}

// ---------------------------------------------------------------------------------------------
// mesh_force

namespace {

Plot sweep_plot(const std::string& plot_name, const std::string& title, const std::string& y_label,
                const gear::MeshSweepResult& r, double (*field)(const gear::MeshSweepPoint&)) {
  Plot p;
  p.name = plot_name;
  p.title = title;
  p.x_label = "speed of gear 1 [rpm]";
  p.y_label = y_label;
  for (const auto* points : {&r.up, &r.down}) {
    if (points->empty()) continue;
    std::vector<double> x, y;
    for (const gear::MeshSweepPoint& q : *points) {
      x.push_back(q.speed_rpm);
      y.push_back(field(q));
    }
    p.traces.push_back(line(points == &r.up ? "sweep up" : "sweep down", std::move(x), std::move(y),
                            Trace::Mode::LinesMarkers, points == &r.up ? "" : "dash"));
  }
  return p;
}

}  // namespace

AnalysisOutput run_mesh_force(const model::Model& model, const model::MeshForceSettings& settings,
                              const std::string& name, Progress& progress) {
  const PairModel pm = build_pair_model(model, pair_index(model, settings.pair));
  const int z1 = pm.pair->teeth1;
  const gear::DynamicMesh mesh(*pm.ste, pm.mesh_options(settings.model, settings.contact_loss));
  const bool dynamic = settings.model == model::MeshForceModel::Dynamic;

  gear::MeshSweepOptions sweep;
  for (double omega : settings.speeds)
    sweep.mesh_frequencies_hz.push_back(mesh_frequency(omega, z1));
  sweep.teeth = z1;
  sweep.direction = settings.direction == model::SweepDirectionKind::Up ? gear::SweepDirection::Up
                    : settings.direction == model::SweepDirectionKind::Down
                        ? gear::SweepDirection::Down
                        : gear::SweepDirection::Both;
  const gear::MeshSweepResult r = gear::sweep_mesh_frequency(mesh, sweep, progress);

  AnalysisOutput out;
  if (!r.up.empty())
    out.tables.push_back(gear::MeshSweepResult::table(
        r.up, "sweep_up",
        fmt::format("Dynamic mesh force of '{}' versus speed of gear 1, sweep up", pm.pair->name)));
  if (!r.down.empty())
    out.tables.push_back(gear::MeshSweepResult::table(
        r.down, "sweep_down",
        fmt::format("Dynamic mesh force of '{}' versus speed of gear 1, sweep down (in the order "
                    "computed)",
                    pm.pair->name)));
  out.plots.push_back(sweep_plot("dynamic_factor", "Dynamic factor F_max / F_s", "F_max / F_s", r,
                                 [](const gear::MeshSweepPoint& q) { return q.dynamic_factor; }));
  out.plots.push_back(sweep_plot("dte_rms", "RMS of the dynamic transmission error (fluctuation)",
                                 "DTE RMS [um]", r,
                                 [](const gear::MeshSweepPoint& q) { return q.dte_rms_m * 1e6; }));
  out.plots.push_back(
      sweep_plot("contact_loss", "Fraction of time without tooth contact", "contact loss [-]", r,
                 [](const gear::MeshSweepPoint& q) { return q.contact_loss_fraction; }));

  out.notes.push_back(fmt::format(
      "Pair '{}': F_s = {:.6g} N, k_mean = {:.6g} N/m, {}; mesh frequency f_m = {} n1 / 60.",
      pm.pair->name, pm.static_force_n, mesh.mean_stiffness_n_m(),
      dynamic ? fmt::format("m_e = {:.6g} kg, zeta = {:.4g} (c = {:.6g} N s/m)",
                            mesh.options().equivalent_mass_kg, pm.pair->mesh_damping_ratio,
                            mesh.damping_n_s_m())
              : std::string("infinite inertias: F_d(t) = F_s k(t) / k_mean (no dynamics)"),
      z1));
  if (dynamic) {
    const double fn = mesh.natural_frequency_hz();
    out.notes.push_back(fmt::format(
        "Mesh resonance: f_n = sqrt(k_mean / m_e) / 2 pi = {:.6g} Hz, met by the mesh frequency at "
        "gear 1 speed {} (half of it, the second mesh harmonic, at {}).",
        fn, rpm_text(60.0 * fn / z1), rpm_text(30.0 * fn / z1)));
  }
  out.notes.push_back(
      "Each speed starts from the steady state of the previous one (continuation), so a jump "
      "between the up and down sweeps is the hysteresis of contact loss, not a numerical "
      "artefact. The steady state is exact for the piecewise-constant stiffness to the "
      "Poincaré tolerance 1e-9.");

  // Contact loss, and the points without a steady state: reported, never hidden.
  std::vector<std::string> failed;
  double loss_min = -1.0, loss_max = -1.0;
  for (const auto* points : {&r.up, &r.down}) {
    for (const gear::MeshSweepPoint& q : *points) {
      if (q.status != Status::Ok)
        failed.push_back(fmt::format("{} ({}, sweep {})", rpm_text(q.speed_rpm),
                                     to_string(q.status), points == &r.up ? "up" : "down"));
      else if (q.contact_loss_fraction > 0.0) {
        loss_min = loss_min < 0.0 ? q.speed_rpm : std::min(loss_min, q.speed_rpm);
        loss_max = std::max(loss_max, q.speed_rpm);
      }
    }
  }
  if (loss_min >= 0.0)
    out.notes.push_back(fmt::format(
        "CONTACT LOSS: the teeth separate during part of the mesh cycle between {} and {} (see "
        "the contact_loss column){}. The mesh is nonlinear there: the dynamic factor and the "
        "harmonics depend on the sweep direction.",
        rpm_text(loss_min), rpm_text(loss_max),
        settings.contact_loss ? "" : " — but contact_loss = false, so the model lets them pull"));
  else if (dynamic)
    out.notes.push_back("No contact loss at any computed speed: the mesh stays in contact.");

  // Time histories at the requested speeds, each from the static equilibrium.
  if (!settings.detail_speeds.empty()) {
    Plot force, dte;
    force.name = "detail_force";
    force.title = "Dynamic mesh force over one period of the steady state";
    force.x_label = "mesh cycles [-]";
    force.y_label = "F_d [N]";
    dte.name = "detail_dte";
    dte.title = "Dynamic transmission error over one period of the steady state";
    dte.x_label = "mesh cycles [-]";
    dte.y_label = "DTE [um]";
    for (double omega : settings.detail_speeds) {
      const double rpm = to_rpm(omega);
      const gear::MeshResponse d = mesh.solve(mesh_frequency(omega, z1));
      if (d.status != Status::Ok) {
        failed.push_back(
            fmt::format("{} (detail: {}; {})", rpm_text(rpm), to_string(d.status), d.message));
        continue;
      }
      const std::string label = fmt::format("{:.6g} rpm", rpm);
      std::vector<double> cycles = scaled(d.time_s, d.mesh_frequency_hz);
      Table t;
      t.name = fmt::format("detail_{:.0f}rpm", rpm);
      t.title = fmt::format(
          "Steady state at gear 1 speed {} (f_m = {:.6g} Hz, period {} mesh "
          "cycle{})",
          rpm_text(rpm), d.mesh_frequency_hz, d.period_cycles, d.period_cycles == 1 ? "" : "s");
      t.add("time_s", "s", d.time_s);
      t.add("mesh_cycles", "", cycles);
      t.add("dte_m", "m", d.dte_m);
      t.add("velocity_m_s", "m/s", d.velocity_m_s);
      t.add("contact_force_n", "N", d.contact_force_n);
      t.add("force_n", "N", d.force_n);
      bool duplicate = false;
      for (const Table& other : out.tables) duplicate = duplicate || other.name == t.name;
      if (duplicate) t.name += fmt::format("_{}", out.tables.size());
      force.traces.push_back(line(label, cycles, d.force_n));
      dte.traces.push_back(line(label, cycles, scaled(d.dte_m, 1e6)));
      out.tables.push_back(std::move(t));
      if (!d.message.empty()) out.notes.push_back(fmt::format("At {}: {}", label, d.message));
    }
    out.plots.push_back(std::move(force));
    out.plots.push_back(std::move(dte));
  }

  if (!failed.empty()) {
    std::string list;
    for (const auto& f : failed) list += (list.empty() ? "" : "; ") + f;
    out.status = r.status != Status::Ok ? r.status : Status::NotConverged;
    out.message = fmt::format(
        "analysis '{}': no periodic steady state of the mesh at {} speed{}: {}. {} What usually "
        "helps: more mesh damping (mesh_damping_ratio), a finer speed grid near the resonance, "
        "or model = \"infinite_inertia\" far below the mesh resonance.",
        name, failed.size(), failed.size() == 1 ? "" : "s", list, r.message);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// mesh_harmonics

namespace {

/// "h", "N-h", "N+h", "2N-h", ... for order k and nodal diameter h of a gear with N teeth.
std::string branch_of(int k, int h, int teeth) {
  const int q = k / teeth, r = k % teeth;
  if (h == 0) return q == 1 ? "N" : fmt::format("{}N", q);
  if (r == h) return q == 0 ? "h" : (q == 1 ? "N+h" : fmt::format("{}N+h", q));
  const int m = q + 1;  // k = m N - h
  return m == 1 ? "N-h" : fmt::format("{}N-h", m);
}

}  // namespace

AnalysisOutput run_mesh_harmonics(const model::Model& model,
                                  const model::MeshHarmonicsSettings& settings,
                                  const std::string& name, Progress& progress) {
  const PairModel pm = build_pair_model(model, pair_index(model, settings.pair));
  const int z1 = pm.pair->teeth1;
  const bool dynamic = settings.model == model::MeshForceModel::Dynamic;

  progress.start("mesh harmonics", 1);
  ToothForceOptions options;
  options.gear = settings.gear;
  options.speed = settings.speed;
  options.model = settings.model;
  options.contact_loss = settings.contact_loss;
  options.window_shift = settings.window_shift;
  options.contact_ratio = settings.contact_ratio;
  const ToothForceRevolution rev = tooth_force_over_revolution(pm, options, name);
  progress.update(1);
  progress.finish();
  const gear::MeshResponse& d = rev.mesh;
  const double fm = rev.mesh_frequency_hz;
  const int teeth = rev.teeth;
  const std::size_t n = static_cast<std::size_t>(rev.tooth.size());
  const gear::ToothForces& member = rev.member;
  const Eigen::VectorXd& mesh_force = rev.mesh_force;
  const Eigen::VectorXd& tangential = rev.tangential;
  const double cr = rev.contact_ratio;
  const Eigen::VectorXd& tooth = rev.tooth;
  const Eigen::VectorXd& window = rev.window;

  AnalysisOutput out;
  {
    Table t;
    t.name = "tooth_load";
    t.title = fmt::format("Load of one tooth of gear {} over one revolution at gear 1 speed {}",
                          settings.gear, rpm_text(to_rpm(settings.speed)));
    std::vector<double> angle(n), fd(n), ft(n), w(n), f(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      angle[i] = 360.0 * static_cast<double>(i) / static_cast<double>(n);
      fd[i] = mesh_force[k];
      ft[i] = tangential[k];
      w[i] = window[k];
      f[i] = tooth[k];
    }
    t.add("angle_deg", "deg", angle);
    t.add("mesh_force_n", "N", fd);
    t.add("tangential_mesh_force_n", "N", ft);
    t.add("window", "", w);
    t.add("force_n", "N", f);
    Plot p;
    p.name = "tooth_load";
    p.title = t.title;
    p.x_label = fmt::format("rotation of gear {} [deg]", settings.gear);
    p.y_label = "tangential force [N]";
    p.traces.push_back(line("mesh force (tangential)", angle, ft, Trace::Mode::Lines, "dot"));
    p.traces.push_back(line("one tooth", angle, f));
    out.plots.push_back(std::move(p));
    out.tables.push_back(std::move(t));
  }

  const int max_order = settings.max_order > 0 ? settings.max_order : 2 * teeth;
  if (static_cast<std::size_t>(max_order) > n / 2)
    throw InputError(SourceLocation{}, "max_order",
                     fmt::format("an order <= {} (half the samples of one revolution)", n / 2),
                     std::to_string(max_order));
  Table spectrum = gear::order_spectrum_table(tooth, max_order, member.tangential_n);
  {
    Plot p;
    p.name = "order_spectrum";
    p.title =
        fmt::format("Order spectrum of the tooth force of gear {} (N = {})", settings.gear, teeth);
    p.x_label = fmt::format("engine order of gear {} [-]", settings.gear);
    p.y_label = "tangential amplitude [N]";
    std::vector<double> k = spectrum.column("order").numbers;
    std::vector<double> a = spectrum.column("amplitude_n").numbers;
    // Order 0 is the mean, not a harmonic: left out of the plot.
    k.erase(k.begin());
    a.erase(a.begin());
    p.traces.push_back(line("amplitude", k, a, Trace::Mode::Markers));
    out.plots.push_back(std::move(p));
  }
  out.tables.push_back(std::move(spectrum));

  std::vector<int> diameters = settings.nodal_diameters;
  if (diameters.empty())
    for (int h = 0; h <= teeth / 2; ++h) diameters.push_back(h);
  const gear::ForceDirections& directions = rev.directions;
  const std::vector<gear::HarmonicComponents> harmonics =
      gear::harmonic_components(tooth, teeth, diameters, directions, settings.orders_per_diameter);
  {
    const double gear_speed_hz =
        settings.speed / kTwoPi * (settings.gear == 1 ? 1.0 : static_cast<double>(z1) / teeth);
    Table t;
    t.name = "harmonics";
    t.title = fmt::format(
        "Engine-order harmonics of the tooth force of gear {} per nodal diameter (one-sided "
        "amplitudes; radial and axial signed relative to the tangential phase)",
        settings.gear);
    std::vector<double> nd, order, freq, amp, phase, ft, fr, fa, rel;
    std::vector<std::string> branch;
    for (const gear::HarmonicComponents& c : harmonics) {
      const double at = std::abs(c.tangential);
      // The ratios are real, so radial and axial are in phase (or opposite) with the
      // tangential harmonic: signed amplitudes keep that sign.
      auto signed_amplitude = [&](std::complex<double> x) {
        return at > 0.0 ? std::real(x * std::conj(c.tangential)) / at : std::abs(x);
      };
      nd.push_back(c.nodal_diameter);
      order.push_back(c.order);
      branch.push_back(branch_of(c.order, c.nodal_diameter, teeth));
      freq.push_back(c.order * gear_speed_hz);
      amp.push_back(std::sqrt(std::norm(c.tangential) + std::norm(c.radial) + std::norm(c.axial)));
      phase.push_back(std::arg(c.tangential) * kDeg);
      ft.push_back(at);
      fr.push_back(signed_amplitude(c.radial));
      fa.push_back(signed_amplitude(c.axial));
      rel.push_back(at / member.tangential_n);
    }
    t.add("nodal_diameter", "", nd);
    t.add("engine_order", "", order);
    t.add_text("branch", branch);
    t.add("frequency_hz", "Hz", freq);
    t.add("amplitude_n", "N", amp);
    t.add("phase_deg", "deg", phase);
    t.add("tangential_n", "N", ft);
    t.add("radial_n", "N", fr);
    t.add("axial_n", "N", fa);
    t.add("amplitude_per_static_force", "", rel);
    out.tables.push_back(std::move(t));
  }

  out.notes.push_back(fmt::format(
      "Gear 1 speed {} (gear {} with N = {} teeth), mesh frequency {:.6g} Hz; {} mesh model: "
      "dynamic factor {:.4f}, contact loss {:.3g} of the time{}.",
      rpm_text(to_rpm(settings.speed)), settings.gear, teeth, fm,
      dynamic ? "dynamic" : "infinite-inertia", d.dynamic_factor, d.contact_loss_fraction,
      d.period_cycles > 1 ? fmt::format(", period {} mesh cycles", d.period_cycles) : ""));
  out.notes.push_back(fmt::format(
      "Tooth-load window: contact ratio {:.4f}{}, shift {:.4g} pitches; static tangential tooth "
      "force F_t = {:.6g} N (T / r of gear {}), radial / tangential = {:.4f}, axial / tangential "
      "= {:.4f} ({} flank of gear {} loaded).",
      cr, std::isnan(settings.contact_ratio) ? " (total contact ratio)" : "", settings.window_shift,
      member.tangential_n, settings.gear, directions.radial_per_tangential,
      directions.axial_per_tangential,
      gear::to_string(settings.gear == 1 ? pm.drive_forces.pinion_flank
                                         : pm.drive_forces.wheel_flank),
      settings.gear));
  out.notes.push_back(
      "Phases are cosine phases in the rotation angle of the gear, zero when the loaded tooth "
      "enters contact (the STE cycle start); a mode with h nodal diameters is excited by the "
      "orders k = h and k = N - h first (DESIGN 4.4). Order 0 of the spectrum is the mean tooth "
      "load, not a harmonic.");
  return out;
}

// ---------------------------------------------------------------------------------------------
// correlation

namespace {

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

AnalysisOutput run_correlation(const model::Model& model,
                               const model::CorrelationSettings& settings, const std::string& name,
                               Progress& progress) {
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

}  // namespace geardyn::gearan
