#include "geardyn/analyses/mesh_harmonics.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <vector>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/tooth_forces.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;
/// Degrees per radian, as the tables have always multiplied by it (bit for bit).
constexpr double kDeg = 180.0 / units::kPi;

/// "h", "N-h", "N+h", "2N-h", ... for order k and nodal diameter h of a gear with N teeth.
std::string branch_of(int k, int h, int teeth) {
  const int q = k / teeth, r = k % teeth;
  if (h == 0) return q == 1 ? "N" : fmt::format("{}N", q);
  if (r == h) return q == 0 ? "h" : (q == 1 ? "N+h" : fmt::format("{}N+h", q));
  const int m = q + 1;  // k = m N - h
  return m == 1 ? "N-h" : fmt::format("{}N-h", m);
}

/// Table and plot of the load of one tooth over one revolution.
void add_tooth_load(AnalysisOutput& out, const MeshHarmonicsSettings& settings,
                    const ToothForceRevolution& rev) {
  const std::size_t n = static_cast<std::size_t>(rev.tooth.size());
  Table t;
  t.name = "tooth_load";
  t.title = fmt::format("Load of one tooth of gear {} over one revolution at gear 1 speed {}",
                        settings.gear, rpm_text(to_rpm(settings.speed)));
  std::vector<double> angle(n), fd(n), ft(n), w(n), f(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    angle[i] = 360.0 * static_cast<double>(i) / static_cast<double>(n);
    fd[i] = rev.mesh_force[k];
    ft[i] = rev.tangential[k];
    w[i] = rev.window[k];
    f[i] = rev.tooth[k];
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

/// Table and plot of the order spectrum of the tooth force.
void add_order_spectrum(AnalysisOutput& out, const MeshHarmonicsSettings& settings,
                        const MeshHarmonicsResult& r) {
  const ToothForceRevolution& rev = r.revolution;
  Table spectrum = gear::order_spectrum_table(rev.tooth, r.max_order, rev.member.tangential_n);
  Plot p;
  p.name = "order_spectrum";
  p.title = fmt::format("Order spectrum of the tooth force of gear {} (N = {})", settings.gear,
                        rev.teeth);
  p.x_label = fmt::format("engine order of gear {} [-]", settings.gear);
  p.y_label = "tangential amplitude [N]";
  std::vector<double> k = spectrum.column("order").numbers;
  std::vector<double> a = spectrum.column("amplitude_n").numbers;
  // Order 0 is the mean, not a harmonic: left out of the plot.
  k.erase(k.begin());
  a.erase(a.begin());
  p.traces.push_back(line("amplitude", k, a, Trace::Mode::Markers));
  out.plots.push_back(std::move(p));
  out.tables.push_back(std::move(spectrum));
}

/// Table of the engine-order harmonics per nodal diameter.
Table harmonics_table(const MeshHarmonicsSettings& settings, const MeshHarmonicsResult& r) {
  const ToothForceRevolution& rev = r.revolution;
  const int teeth = rev.teeth;
  const int z1 = r.pair.pair->teeth1;
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
  for (const gear::HarmonicComponents& c : r.harmonics) {
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
    rel.push_back(at / rev.member.tangential_n);
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
  return t;
}

/// The notes on the mesh model, the tooth-load window and the phases.
void add_notes(AnalysisOutput& out, const MeshHarmonicsSettings& settings,
               const MeshHarmonicsResult& r) {
  const ToothForceRevolution& rev = r.revolution;
  const gear::MeshResponse& d = rev.mesh;
  const PairModel& pm = r.pair;
  out.notes.push_back(fmt::format(
      "Gear 1 speed {} (gear {} with N = {} teeth), mesh frequency {:.6g} Hz; {} mesh model: "
      "dynamic factor {:.4f}, contact loss {:.3g} of the time{}.",
      rpm_text(to_rpm(settings.speed)), settings.gear, rev.teeth, rev.mesh_frequency_hz,
      settings.model == MeshForceModel::Dynamic ? "dynamic" : "infinite-inertia", d.dynamic_factor,
      d.contact_loss_fraction,
      d.period_cycles > 1 ? fmt::format(", period {} mesh cycles", d.period_cycles) : ""));
  out.notes.push_back(fmt::format(
      "Tooth-load window: contact ratio {:.4f}{}, shift {:.4g} pitches; static tangential tooth "
      "force F_t = {:.6g} N (T / r of gear {}), radial / tangential = {:.4f}, axial / tangential "
      "= {:.4f} ({} flank of gear {} loaded).",
      rev.contact_ratio, std::isnan(settings.contact_ratio) ? " (total contact ratio)" : "",
      settings.window_shift, rev.member.tangential_n, settings.gear,
      rev.directions.radial_per_tangential, rev.directions.axial_per_tangential,
      gear::to_string(settings.gear == 1 ? pm.drive_forces.pinion_flank
                                         : pm.drive_forces.wheel_flank),
      settings.gear));
  out.notes.push_back(
      "Phases are cosine phases in the rotation angle of the gear, zero when the loaded tooth "
      "enters contact (the STE cycle start); a mode with h nodal diameters is excited by the "
      "orders k = h and k = N - h first (docs/theory.md §12.3). Order 0 of the spectrum is the "
      "mean tooth load, not a harmonic.");
}

}  // namespace

MeshHarmonicsResult run_mesh_harmonics(const model::Model& model,
                                       const MeshHarmonicsSettings& settings,
                                       const Context& context) {
  MeshHarmonicsResult r{
      build_pair_model(model, pair_index(model, settings.pair)), {}, 0, {}, {}, {}};
  Progress& progress = context.progress();
  progress.start("mesh harmonics", 1);
  ToothForceOptions options;
  options.gear = settings.gear;
  options.speed = settings.speed;
  options.model = settings.model;
  options.contact_loss = settings.contact_loss;
  options.window_shift = settings.window_shift;
  options.contact_ratio = settings.contact_ratio;
  r.revolution = tooth_force_over_revolution(r.pair, options, context.name());
  progress.update(1);
  progress.finish();
  const ToothForceRevolution& rev = r.revolution;
  const int teeth = rev.teeth;
  const std::size_t n = static_cast<std::size_t>(rev.tooth.size());

  r.max_order = settings.max_order > 0 ? settings.max_order : 2 * teeth;
  if (static_cast<std::size_t>(r.max_order) > n / 2)
    throw context.error("max_order",
                        fmt::format("an order <= {} (half the samples of one revolution)", n / 2),
                        std::to_string(r.max_order));
  r.order_amplitude_n = gear::order_spectrum_table(rev.tooth, r.max_order, rev.member.tangential_n)
                            .column("amplitude_n")
                            .numbers;

  r.diameters = settings.nodal_diameters;
  if (r.diameters.empty())
    for (int h = 0; h <= teeth / 2; ++h) r.diameters.push_back(h);
  r.harmonics = gear::harmonic_components(rev.tooth, teeth, r.diameters, rev.directions,
                                          settings.orders_per_diameter);
  return r;
}

AnalysisOutput mesh_harmonics_output(const model::Model& /*model*/,
                                     const MeshHarmonicsSettings& settings,
                                     const MeshHarmonicsResult& result,
                                     const Context& /*context*/) {
  AnalysisOutput out;
  add_tooth_load(out, settings, result.revolution);
  add_order_spectrum(out, settings, result);
  out.tables.push_back(harmonics_table(settings, result));
  add_notes(out, settings, result);
  return out;
}

void check_mesh_harmonics_inputs(const model::Model& model, const MeshHarmonicsSettings& h,
                                 const Context& context) {
  const PairModel pm = build_pair_model(model, pair_index(model, h.pair));
  const int teeth = h.gear == 1 ? pm.pair->teeth1 : pm.pair->teeth2;
  const double cr = std::isnan(h.contact_ratio) ? pm.geometry.total_contact_ratio : h.contact_ratio;
  if (!(cr >= 1.0 && cr <= 3.0 && cr < teeth))
    throw context.error(
        "contact_ratio",
        fmt::format("a tooth-load window contact ratio in [1, 3] and below the "
                    "{} teeth of gear {}",
                    teeth, h.gear),
        fmt::format("{:.6g}{}", cr,
                    std::isnan(h.contact_ratio)
                        ? fmt::format(" (the total contact ratio of pair '{}')", pm.pair->name)
                        : ""),
        "give contact_ratio for the window explicitly");
  if (h.max_order > 64 * teeth)
    throw context.error("max_order",
                        fmt::format("an order <= 64 N = {} (resolved by the samples of one "
                                    "revolution)",
                                    64 * teeth),
                        std::to_string(h.max_order));
}

}  // namespace geardyn::analyses
