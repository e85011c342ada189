#include "geardyn/analyses/mesh_force.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;

/// Mesh frequency [Hz] at gear 1's speed `omega1` [rad/s]: f_m = z1 omega1 / 2 pi.
double mesh_frequency(double omega1, int teeth1) { return teeth1 * omega1 / kTwoPi; }

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

/// The notes on the mesh model, its resonance and the continuation.
void add_model_notes(AnalysisOutput& out, const MeshForceSettings& settings,
                     const MeshForceResult& r) {
  const PairModel& pm = r.pair;
  const int z1 = pm.pair->teeth1;
  const bool dynamic = settings.model == MeshForceModel::Dynamic;
  out.notes.push_back(fmt::format(
      "Pair '{}': F_s = {:.6g} N, k_mean = {:.6g} N/m, {}; mesh frequency f_m = {} n1 / 60.",
      pm.pair->name, pm.static_force_n, r.mean_stiffness_n_m,
      dynamic ? fmt::format("m_e = {:.6g} kg, zeta = {:.4g} (c = {:.6g} N s/m)",
                            r.equivalent_mass_kg, pm.pair->mesh_damping_ratio, r.damping_n_s_m)
              : std::string("infinite inertias: F_d(t) = F_s k(t) / k_mean (no dynamics)"),
      z1));
  if (dynamic) {
    out.notes.push_back(
        settings.damping_on == MeshDampingKind::Dte
            ? std::string("Mesh damping on the dynamic transmission error: c x', in and out of "
                          "contact (damping_on = \"dte\").")
            : std::string("Mesh damping on the elastic deflection of the teeth: c (x' - e_g'), "
                          "in contact only, none while the teeth are apart (damping_on = "
                          "\"elastic_deflection\"; after Kahraman & Singh 1990)."));
    if (settings.force_amplitude > 0.0)
      out.notes.push_back(fmt::format(
          "External harmonic force on the mesh coordinate: F_a = {:.6g} N at {} x f_m, phase "
          "{:.6g} deg at the cycle start, added to F_s.",
          settings.force_amplitude, settings.force_order,
          settings.force_phase / units::kRadPerDegree));
    const double fn = r.natural_frequency_hz;
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
}

/// The contact-loss note; the sweep points without a steady state are added to `failed`.
void add_contact_loss_note(AnalysisOutput& out, const MeshForceSettings& settings,
                           const gear::MeshSweepResult& r, std::vector<std::string>& failed) {
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
  else if (settings.model == MeshForceModel::Dynamic)
    out.notes.push_back("No contact loss at any computed speed: the mesh stays in contact.");
}

/// The time histories at the detail speeds (tables and two plots); failures go to `failed`.
void add_details(AnalysisOutput& out, const MeshForceResult& r, std::vector<std::string>& failed) {
  if (r.details.empty()) return;
  Plot force, dte;
  force.name = "detail_force";
  force.title = "Dynamic mesh force over one period of the steady state";
  force.x_label = "mesh cycles [-]";
  force.y_label = "F_d [N]";
  dte.name = "detail_dte";
  dte.title = "Dynamic transmission error over one period of the steady state";
  dte.x_label = "mesh cycles [-]";
  dte.y_label = "DTE [um]";
  for (const MeshForceDetail& detail : r.details) {
    const double rpm = to_rpm(detail.speed);
    const gear::MeshResponse& d = detail.response;
    if (d.status != Status::Ok) {
      failed.push_back(
          fmt::format("{} (detail: {}; {})", rpm_text(rpm), to_string(d.status), d.message));
      continue;
    }
    const std::string label = fmt::format("{:.6g} rpm", rpm);
    std::vector<double> cycles = scaled(d.time_s, d.mesh_frequency_hz);
    Table t;
    // Named by the speed as given (to 10 digits, so 1000.4 and 1000.2 rpm stay apart), and the
    // speed written in the table too.
    t.name = fmt::format("detail_{:.10g}rpm", rpm);
    t.title = fmt::format(
        "Steady state at gear 1 speed {} (f_m = {:.6g} Hz, period {} mesh "
        "cycle{})",
        rpm_text(rpm), d.mesh_frequency_hz, d.period_cycles, d.period_cycles == 1 ? "" : "s");
    t.add("speed_rpm", "rpm", std::vector<double>(d.time_s.size(), rpm));
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

/// Damping on the elastic deflection needs a continuous e_g: with a held curve whose e_g steps,
/// c (x' - e_g') would be an impulse at each step.
void check_elastic_damping(const PairModel& pm, const MeshForceSettings& settings,
                           const Context& context) {
  if (settings.damping_on != MeshDampingKind::ElasticDeflection ||
      settings.model != MeshForceModel::Dynamic)
    return;
  const auto& g = pm.ste->geometric_te_m();
  if (pm.ste->interpolation() == gear::SteInterpolation::Hold &&
      std::any_of(g.begin(), g.end(), [&](double v) { return v != g.front(); }))
    throw context.error(
        "damping_on", "a continuous unloaded TE e_g for damping on the elastic deflection",
        fmt::format("gear pair '{}' with a step (hold) STE whose unloaded TE varies: the damper "
                    "force c (x' - e_g') would be an impulse at each step",
                    pm.pair->name),
        "use damping_on = \"dte\", or ste_interpolation = \"linear\" for the gear pair");
}

}  // namespace

void check_mesh_force_inputs(const model::Model& model, const MeshForceSettings& settings,
                             const Context& context) {
  check_elastic_damping(build_pair_model(model, pair_index(model, settings.pair)), settings,
                        context);
}

MeshForceResult run_mesh_force(const model::Model& model, const MeshForceSettings& settings,
                               const Context& context) {
  MeshForceResult r{build_pair_model(model, pair_index(model, settings.pair)),
                    {},
                    0.0,
                    0.0,
                    0.0,
                    model::kNaN,
                    {}};
  const PairModel& pm = r.pair;
  const int z1 = pm.pair->teeth1;
  gear::DynamicMeshOptions options = pm.mesh_options(settings.model, settings.contact_loss);
  const bool elastic = settings.damping_on == MeshDampingKind::ElasticDeflection;
  options.damping_on = elastic ? gear::MeshDamping::ElasticDeflection : gear::MeshDamping::Dte;
  options.force_amplitude_n = settings.force_amplitude;
  options.force_order = settings.force_order;
  options.force_phase_rad = settings.force_phase;
  check_elastic_damping(pm, settings, context);
  const gear::DynamicMesh mesh(*pm.ste, options);
  r.mean_stiffness_n_m = mesh.mean_stiffness_n_m();
  r.damping_n_s_m = mesh.damping_n_s_m();
  r.equivalent_mass_kg = mesh.options().equivalent_mass_kg;
  if (settings.model == MeshForceModel::Dynamic)
    r.natural_frequency_hz = mesh.natural_frequency_hz();

  gear::MeshSweepOptions sweep;
  for (double omega : settings.speeds)
    sweep.mesh_frequencies_hz.push_back(mesh_frequency(omega, z1));
  sweep.teeth = z1;
  sweep.direction = settings.direction == SweepDirectionKind::Up     ? gear::SweepDirection::Up
                    : settings.direction == SweepDirectionKind::Down ? gear::SweepDirection::Down
                                                                     : gear::SweepDirection::Both;
  r.sweep = gear::sweep_mesh_frequency(mesh, sweep, context.progress());

  // Time histories at the requested speeds, each from the static equilibrium.
  for (double omega : settings.detail_speeds)
    r.details.push_back({omega, mesh.solve(mesh_frequency(omega, z1))});
  return r;
}

AnalysisOutput mesh_force_output(const model::Model& /*model*/, const MeshForceSettings& settings,
                                 const MeshForceResult& result, const Context& context) {
  const PairModel& pm = result.pair;
  const gear::MeshSweepResult& r = result.sweep;
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
  add_model_notes(out, settings, result);

  // Contact loss, and the points without a steady state: reported, never hidden.
  std::vector<std::string> failed;
  add_contact_loss_note(out, settings, r, failed);
  add_details(out, result, failed);

  if (!failed.empty()) {
    std::string list;
    for (const auto& f : failed) list += (list.empty() ? "" : "; ") + f;
    const std::string what = fmt::format(
        "no periodic steady state of the mesh at {} speed{}: {}. {} What usually helps: more "
        "mesh damping (mesh_damping_ratio), a finer speed grid near the resonance, or model = "
        "\"infinite_inertia\" far below the mesh resonance.",
        failed.size(), failed.size() == 1 ? "" : "s", list, r.message);
    // A speed without a periodic steady state (quasi-periodic or chaotic) is a finding about
    // the mesh, reported per speed in the tables; only when no speed has one has the analysis
    // no result.
    std::size_t ok_points = 0;
    for (const auto* points : {&r.up, &r.down})
      for (const gear::MeshSweepPoint& q : *points) ok_points += q.status == Status::Ok;
    if (ok_points == 0) {
      out.status = r.status != Status::Ok ? r.status : Status::NotConverged;
      out.message = fmt::format("analysis '{}': {}", context.name(), what);
    } else {
      out.notes.push_back("NO STEADY STATE: " + what +
                          " The status and message columns of the sweep tables say which "
                          "speeds.");
    }
  }
  return out;
}

}  // namespace geardyn::analyses
