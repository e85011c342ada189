#include "geardyn/analyses/mesh_harmonics.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/gear/tooth_forces.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDeg = 180.0 / std::numbers::pi;

/// "h", "N-h", "N+h", "2N-h", ... for order k and nodal diameter h of a gear with N teeth.
std::string branch_of(int k, int h, int teeth) {
  const int q = k / teeth, r = k % teeth;
  if (h == 0) return q == 1 ? "N" : fmt::format("{}N", q);
  if (r == h) return q == 0 ? "h" : (q == 1 ? "N+h" : fmt::format("{}N+h", q));
  const int m = q + 1;  // k = m N - h
  return m == 1 ? "N-h" : fmt::format("{}N-h", m);
}

}  // namespace

AnalysisOutput run_mesh_harmonics(const model::Model& model, const MeshHarmonicsSettings& settings,
                                  const std::string& name, Progress& progress) {
  const PairModel pm = build_pair_model(model, pair_index(model, settings.pair));
  const int z1 = pm.pair->teeth1;
  const bool dynamic = settings.model == MeshForceModel::Dynamic;

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

}  // namespace geardyn::analyses
