#include "geardyn/analyses/cyclic_forced_response.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <set>
#include <vector>

#include "geardyn/analyses/damper_ring_response.hpp"
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/gear_forced_response.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;
constexpr double kRpm = 60.0 / units::kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / units::kPi;

/// Drops the superposed columns of the library's response table.
Table without_superposition(const Table& t) {
  Table out;
  out.name = t.name;
  out.title = t.title;
  for (const Column& c : t.columns)
    if (c.name.find("_sum_amplitude_") == std::string::npos &&
        !(c.name.size() > 6 && (c.name.ends_with("_rms_m") || c.name.ends_with("_rms_rad"))))
      out.columns.push_back(c);
  return out;
}

// --- set-up

/// The sector solved and its cyclic interfaces: the assembled mesh or its Craig-Bampton
/// reduction (masters: the interfaces, the excitation and sensor nodes and the master sets;
/// docs/theory.md §9).
struct Sector {
  SolvedSector solved;
  cyclic::CyclicSector cyclic;
};

Sector sector_of(const assembly::SolidComponent& c, const CyclicForcedResponseSettings& s,
                 const SectorPoints& points, const Context& context) {
  const std::vector<solid::DofInfo> mesh_dofs = c.dofs();
  cyclic::InterfaceOptions io;
  io.n_sectors = c.sectors;
  io.tolerance = c.interface_tolerance;
  const cyclic::SectorInterfaces mesh_interfaces = cyclic::find_interfaces(mesh_dofs, io);
  std::vector<long> left_ids, right_ids;
  for (const auto& pr : mesh_interfaces.pairs) {
    left_ids.push_back(pr.left_node_id);
    right_ids.push_back(pr.right_node_id);
  }
  std::vector<long> masters = left_ids;
  masters.insert(masters.end(), right_ids.begin(), right_ids.end());
  for (int n : points.excitation) masters.push_back(c.mesh.node_ids[static_cast<std::size_t>(n)]);
  for (int n : points.sensor_nodes) masters.push_back(c.mesh.node_ids[static_cast<std::size_t>(n)]);
  SolvedSector solved =
      solved_sector(c, s, std::move(masters), "interfaces, excitation and sensor nodes", context);
  cyclic::InterfaceOptions rio = io;
  rio.left_nodes = left_ids;
  rio.right_nodes = right_ids;
  cyclic::CyclicSector sector(solved.dofs, cyclic::find_interfaces(solved.dofs, rio));
  return {std::move(solved), std::move(sector)};
}

/// The nodal diameters solved: those listed, else those of the engine orders listed, else
/// 0 .. N / 2.
std::vector<int> nodal_diameters(int N, const CyclicForcedResponseSettings& s) {
  std::vector<int> nds = s.nodal_diameters;
  if (nds.empty() && !s.engine_orders.empty()) {
    std::set<int> from_orders;
    for (int k : s.engine_orders) from_orders.insert(std::min(k % N, N - k % N));
    nds.assign(from_orders.begin(), from_orders.end());
  }
  if (nds.empty())
    for (int h = 0; h <= N / 2; ++h) nds.push_back(h);
  return nds;
}

/// The engine orders k = +-h (mod N) excited per nodal diameter, with their explicit amplitude.
std::vector<OrderForce> excited_orders(int N, const std::vector<int>& nds,
                                       const CyclicForcedResponseSettings& s,
                                       const Context& context) {
  std::vector<OrderForce> orders;
  for (int h : nds) {
    std::vector<int> ks;
    if (s.engine_orders.empty()) {
      ks = gear::nodal_diameter_orders(N, h, s.orders_per_diameter);
    } else {
      for (int k : s.engine_orders)
        if (k % N == h || k % N == (N - h) % N) ks.push_back(k);
    }
    for (int k : ks) {
      OrderForce f;
      f.nodal_diameter = h;
      f.engine_order = k;
      f.amplitude = response::kNaN;
      if (!s.force_amplitude.empty()) {
        std::size_t j = 0;
        if (s.force_amplitude.size() > 1)
          j = static_cast<std::size_t>(
              std::find(s.engine_orders.begin(), s.engine_orders.end(), k) -
              s.engine_orders.begin());
        f.amplitude = s.force_amplitude[j];
      }
      orders.push_back(f);
    }
  }
  if (orders.empty())
    throw context.error("engine_orders", "at least one engine order of a listed nodal diameter",
                        "none");
  return orders;
}

/// The amplitude of order `order_index` (-1: the sum) at sensor `sensor` over speed.
std::vector<double> computed_curve(const response::CyclicForcedResult& r, int order_index,
                                   std::size_t sensor) {
  std::vector<double> a(static_cast<std::size_t>(r.speeds.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const auto col = static_cast<Eigen::Index>(sensor);
    a[i] = order_index < 0
               ? r.amplitude_sum(row, col)
               : std::abs(r.orders[static_cast<std::size_t>(order_index)].displacement(row, col));
  }
  return a;
}

std::vector<double> rpm_of(const std::vector<double>& speeds) {
  std::vector<double> v;
  for (double w : speeds) v.push_back(w * kRpm);
  return v;
}

// --- post-processing

/// Table "harmonic_forces"; `used` gets the amplitude of each order.
Table harmonic_forces_table(int N, const CyclicForcedResponseSettings& s,
                            const std::vector<OrderForce>& orders, std::vector<double>& used) {
  Table t;
  t.name = "harmonic_forces";
  t.title =
      "Harmonic forces per nodal diameter and engine order (one-sided amplitudes; radial and "
      "axial signed relative to the tangential phase, gear/tooth_forces.hpp signs)";
  std::vector<double> nd, eo, ft, fr, fa, phase, total;
  std::vector<std::string> rule;
  for (const OrderForce& f : orders) {
    nd.push_back(f.nodal_diameter);
    eo.push_back(f.engine_order);
    rule.push_back(response::relate_order(N, f.nodal_diameter, f.engine_order).rule);
    if (!s.pair.empty()) {
      // Radial and axial are real multiples of the tangential harmonic: signed amplitudes
      // keep the sign of that ratio (as mesh_harmonics tabulates them).
      const double at = std::abs(f.tangential);
      auto signed_amplitude = [&](Complex x) {
        return at > 0.0 ? std::real(x * std::conj(f.tangential)) / at : std::abs(x);
      };
      ft.push_back(at);
      fr.push_back(signed_amplitude(f.radial));
      fa.push_back(signed_amplitude(f.axial));
      phase.push_back(std::arg(f.tangential) * kDeg);
      total.push_back(
          std::sqrt(std::norm(f.tangential) + std::norm(f.radial) + std::norm(f.axial)));
    } else {
      ft.push_back(s.force_direction ? response::kNaN : f.amplitude);
      fr.push_back(s.force_direction ? response::kNaN : 0.0);
      fa.push_back(s.force_direction ? response::kNaN : 0.0);
      phase.push_back(0.0);
      total.push_back(f.amplitude);
    }
  }
  used = total;
  t.add("nodal_diameter", "", nd);
  t.add("engine_order", "", eo);
  t.add_text("order_rule", rule);
  t.add("tangential_n", "N", ft);
  t.add("radial_n", "N", fr);
  t.add("axial_n", "N", fa);
  t.add("phase_deg", "deg", phase);
  t.add("amplitude_n", "N", total);
  return t;
}

// Comparison with a measured response (Durastante, "Simulation of the Dynamic Response of
// Aeronautical Gears Equipped with Damper Rings", 2018, sec. 5.2): peak speed, amplitude and Q.
void add_measured_comparison(AnalysisOutput& out, const CyclicForcedResponseSettings& s,
                             const CyclicForcedResponseResult& g,
                             const std::vector<double>& force_used,
                             const std::vector<double>& rpm) {
  const response::CyclicForcedResult& result = g.response;
  const std::string curve_name =
      fmt::format("{} {}", result.sensors[g.measured_sensor].name,
                  g.measured_order < 0 ? std::string("sum of orders")
                                       : fmt::format("EO {}", s.measured_engine_order));
  MeasuredComparison mc = compare_with_measured(out, *g.measured, rpm, g.measured_computed,
                                                curve_name, s.min_prominence_db);
  Plot& p = mc.plot;
  if (!mc.peaks.empty() && s.scale_to_measured) {
    // Linear model: scaling every harmonic by A_measured / A_computed reproduces the measured
    // peak; the implied force is the scaled harmonic (Durastante 2018, sec. 5.2).
    const gear::PeakComparison& pc = mc.peaks[mc.main];
    std::vector<double> nd, eo, used;
    for (std::size_t j = 0; j < g.orders.size(); ++j) {
      if (g.measured_order >= 0 && static_cast<int>(j) != g.measured_order) continue;
      nd.push_back(g.orders[j].nodal_diameter);
      eo.push_back(g.orders[j].engine_order);
      used.push_back(force_used[j]);
    }
    out.tables.push_back(force_scaling_table(pc, "Harmonic forces",
                                             {{"nodal_diameter", nd}, {"engine_order", eo}}, used));
    p.traces.push_back(curve("computed, scaled", rpm,
                             computed_curve(result, g.measured_order, g.measured_sensor), "dash"));
    out.notes.push_back(
        fmt::format("scale_to_measured: every harmonic force is multiplied by {:.6g} (table "
                    "force_scaling); the response tables and plots below show the scaled response.",
                    g.scale));
  }
  out.plots.push_back(std::move(p));
}

void add_response_plots(AnalysisOutput& out, const CyclicForcedResponseSettings& s,
                        const response::CyclicForcedResult& result,
                        const std::vector<double>& rpm) {
  for (std::size_t j = 0; j < result.orders.size(); ++j) {
    const response::OrderResponse& o = result.orders[j];
    Plot p = amplitude_plot(
        fmt::format("response_h{}_k{}", o.nodal_diameter, o.engine_order),
        fmt::format("Response to engine order {} (ND {}, {} wave, k = {}) in the rotating frame",
                    o.engine_order, o.nodal_diameter, response::to_string(o.relation.wave),
                    o.relation.rule));
    for (std::size_t k = 0; k < result.sensors.size(); ++k)
      p.traces.push_back(
          curve(result.sensors[k].name, rpm, computed_curve(result, static_cast<int>(j), k)));
    out.plots.push_back(std::move(p));
  }
  if (s.superpose && result.orders.size() > 1) {
    Plot p = amplitude_plot("superposed",
                            "All engine orders superposed: sum of amplitudes (upper "
                            "bound of the peak) and RMS");
    for (std::size_t k = 0; k < result.sensors.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      std::vector<double> sum(rpm.size()), rms(rpm.size());
      for (std::size_t i = 0; i < rpm.size(); ++i) {
        sum[i] = result.amplitude_sum(static_cast<Eigen::Index>(i), col);
        rms[i] = result.amplitude_rms(static_cast<Eigen::Index>(i), col);
      }
      p.traces.push_back(curve(result.sensors[k].name + " sum", rpm, sum));
      p.traces.push_back(curve(result.sensors[k].name + " RMS", rpm, rms, "dot"));
    }
    out.plots.push_back(std::move(p));
  }
}

/// How far to trust it: the modes summed against the excitation, the damping, the frame.
void add_trust_notes(AnalysisOutput& out, const CyclicForcedResponseSettings& s,
                     const CyclicForcedResponseResult& g, const std::string& solid_name, int N) {
  const double w_max = s.speeds.back();
  for (const auto& d : g.modes.diameters) {
    int k_max = 0;
    for (const auto& f : g.orders)
      if (f.nodal_diameter == d.nodal_diameter) k_max = std::max(k_max, f.engine_order);
    if (k_max == 0 || d.frequency_hz.size() == 0) continue;
    const double f_top = d.frequency_hz[d.frequency_hz.size() - 1];
    const double f_exc = k_max * w_max / units::kTwoPi;
    out.notes.push_back(fmt::format(
        "ND {}: {} modes up to {:.6g} Hz summed; the highest excitation frequency is {:.6g} Hz "
        "(EO {} at {:.6g} rpm){}",
        d.nodal_diameter, d.frequency_hz.size(), f_top, f_exc, k_max, w_max * kRpm,
        f_exc > 0.8 * f_top
            ? ": it comes close to or above the highest mode, so resonances of modes left out "
              "may be missing: raise n_modes."
            : "; the modes left out add only their (small) static share, no resonance."));
  }
  out.notes.push_back(fmt::format(
      "Damping: modal damping ratio {:.4g} (Q = {:.4g}) assumed for every mode; the resonance "
      "amplitudes scale with Q, so they are as good as this assumption (correlate with a "
      "measurement: measured_file). Orders superposed as amplitudes (upper bound) and RMS: "
      "their frequencies k W differ, so the phases do not add.",
      std::isnan(s.q_factor) ? s.damping_ratio : 0.5 / s.q_factor,
      std::isnan(s.q_factor) ? 0.5 / s.damping_ratio : s.q_factor));
  out.notes.push_back(fmt::format(
      "Rotating frame: speeds and sensor components are those of the gear (solid '{}'); order "
      "k seen in the rotating frame at k W excites ND h = k mod {} (k = h: backward wave, "
      "standing still under the mesh; k = N - h: forward wave, seen at the mesh frequency in "
      "the stationary frame). Each speed costs a modal sum only.",
      solid_name, N));
}

}  // namespace

std::size_t CyclicForcedResponseResult::sensor_index(const std::string& name) const {
  return requested_sensor(response.sensors, name);
}

std::vector<double> CyclicForcedResponseResult::sum_curve(std::size_t k) const {
  return computed_curve(response, -1, k);
}

CyclicForcedResponseResult run_cyclic_forced_response(const model::Model& model,
                                                      const CyclicForcedResponseSettings& s,
                                                      const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  Progress& progress = context.progress();
  CyclicForcedResponseResult g;
  const SectorPoints points = sector_points(context, c, s);
  const int N = c.sectors;
  const Sector sector = sector_of(c, s, points, context);
  g.reduction_note = sector.solved.note;
  const std::optional<reduce::ReducedComponent>& cb = sector.solved.cb;

  // Nodal diameters and engine orders k = +-h (mod N).
  const std::vector<int> nds = nodal_diameters(N, s);
  g.orders = excited_orders(N, nds, s, context);

  // Tooth-force harmonics from the gear pair, exactly as mesh_harmonics computes them.
  g.force_note =
      !s.pair.empty()
          ? tooth_force_harmonics(model, context, s, g.orders, "engine_orders")
          : fmt::format("Harmonic forces given (force_amplitude), {} at every speed of the range.",
                        s.force_direction ? "along force_direction" : "tangential (-e_theta)");

  // Modes per nodal diameter, once.
  cyclic::CyclicModesOptions mo;
  mo.nodal_diameters = nds;
  // A sector has only so many modes per nodal diameter: asking more gives all of them.
  mo.eigen.n_modes =
      static_cast<int>(std::min<Eigen::Index>(s.n_modes, sector.cyclic.num_reduced_dofs()));
  g.modes =
      cyclic::solve_cyclic_modes(sector.solved.K, sector.solved.M, sector.cyclic, mo, progress);
  if (g.modes.status != Status::Ok) throw NumericalError(context.name(), g.modes.message);

  response::CyclicForcedSettings fs;
  fs.sensors = points.sensors;
  fs.speeds = Eigen::Map<const Eigen::VectorXd>(s.speeds.data(),
                                                static_cast<Eigen::Index>(s.speeds.size()));
  if (!std::isnan(s.q_factor))
    fs.damping.q_factor = s.q_factor;
  else
    fs.damping.damping_ratio = s.damping_ratio;
  auto run = [&](double scale) {
    fs.excitations.clear();
    for (const auto& f : g.orders)
      fs.excitations.push_back(
          {f.nodal_diameter, f.engine_order, order_loads(c, points, s, f, scale)});
    return response::run_cyclic_forced_response(sector.cyclic, g.modes.diameters, fs,
                                                cb ? &*cb : nullptr, progress);
  };
  g.response = run(1.0);
  if (s.measured_file.empty()) return g;

  // The measured curve; scale_to_measured solves again with the forces scaled so that the
  // computed peak matches the largest measured one (linear model).
  g.measured = read_measured(model, context, s.measured_file);
  g.measured_sensor = measured_sensor_index(g.response.sensors, s.measured_sensor, context);
  if (s.measured_engine_order > 0) {
    for (std::size_t j = 0; j < g.orders.size(); ++j)
      if (g.orders[j].engine_order == s.measured_engine_order)
        g.measured_order = static_cast<int>(j);
    if (g.measured_order < 0)
      throw context.error("measured_engine_order",
                          "an engine order of this analysis (or 0: the superposed sum)",
                          std::to_string(s.measured_engine_order));
  }
  g.measured_computed = computed_curve(g.response, g.measured_order, g.measured_sensor);
  if (s.scale_to_measured) {
    const std::vector<gear::PeakComparison> peaks =
        measured_peaks(*g.measured, rpm_of(s.speeds), g.measured_computed, s.min_prominence_db);
    if (!peaks.empty()) {
      const gear::PeakComparison& pc = peaks[largest_measured_peak(peaks)];
      g.scale = pc.measured.amplitude / pc.computed.amplitude;
      g.response = run(g.scale);
    }
  }
  return g;
}

AnalysisOutput cyclic_forced_response_output(const model::Model& model,
                                             const CyclicForcedResponseSettings& s,
                                             const CyclicForcedResponseResult& g,
                                             const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  const response::CyclicForcedResult& result = g.response;
  AnalysisOutput out;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  if (!g.reduction_note.empty()) out.notes.push_back(g.reduction_note);
  out.notes.push_back(g.modes.brief_report());
  const std::vector<double> rpm = rpm_of(s.speeds);
  std::vector<double> force_used;
  out.tables.push_back(result.resonance_table());
  out.tables.push_back(s.superpose ? result.response_table()
                                   : without_superposition(result.response_table()));
  out.tables.push_back(harmonic_forces_table(c.sectors, s, g.orders, force_used));
  out.notes.push_back(g.force_note);
  if (g.measured) add_measured_comparison(out, s, g, force_used, rpm);
  out.tables.push_back(result.peak_table());
  out.tables.push_back(g.modes.table());
  add_response_plots(out, s, result, rpm);
  add_trust_notes(out, s, g, c.name, c.sectors);
  if (!result.message.empty()) out.notes.push_back(result.message);
  out.status = result.status;
  if (result.status != Status::Ok) out.message = result.message;
  return out;
}

// ---------------------------------------------------------------------------------------------
// checks before the run

void check_cyclic_forced_response_inputs(const model::Model& model,
                                         const CyclicForcedResponseSettings& s,
                                         const Context& context) {
  if (const assembly::SolidComponents* solids = context.solids()) {
    const auto it = solids->find(s.solid);
    if (it != solids->end()) (void)sector_points(context, it->second, s);
  }
  if (!s.pair.empty()) {
    const analyses::PairModel pm =
        analyses::build_pair_model(model, analyses::pair_index(model, s.pair));
    const int teeth = s.gear == 1 ? pm.pair->teeth1 : pm.pair->teeth2;
    const double cr =
        std::isnan(s.contact_ratio) ? pm.geometry.total_contact_ratio : s.contact_ratio;
    try {
      (void)gear::tooth_load_window(0.0, teeth, cr);
    } catch (const InputError& e) {
      throw context.error("contact_ratio", e.expected(), e.found(), e.hint());
    }
  }
  if (!s.measured_file.empty()) (void)read_measured(model, context, s.measured_file);
}

}  // namespace geardyn::analyses
