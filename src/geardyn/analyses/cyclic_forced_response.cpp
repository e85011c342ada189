#include "geardyn/analyses/cyclic_forced_response.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
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
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRpm = 60.0 / kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / std::numbers::pi;

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

}  // namespace

AnalysisOutput run_cyclic_forced_response(const model::Model& model,
                                          const assembly::SolidComponent& c,
                                          const CyclicForcedResponseSettings& s,
                                          const std::string& name, Progress& progress) {
  AnalysisOutput out;
  const SourceLocation where = where_of(model, name);
  const SectorPoints points = sector_points(model, name, c, s);
  const int N = c.sectors;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);

  // The sector: the assembled mesh or its Craig-Bampton reduction (masters: the interfaces,
  // the excitation and sensor nodes and the master sets; DESIGN 4.2).
  const std::vector<solid::DofInfo> mesh_dofs = c.dofs();
  cyclic::InterfaceOptions io;
  io.n_sectors = N;
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
  SolvedSector solved = solved_sector(c, s, std::move(masters),
                                      "interfaces, excitation and sensor nodes", name, progress);
  if (!solved.note.empty()) out.notes.push_back(solved.note);
  const std::optional<reduce::ReducedComponent>& cb = solved.cb;
  const std::vector<solid::DofInfo>& dofs = solved.dofs;
  const Eigen::SparseMatrix<double>& K = solved.K;
  const Eigen::SparseMatrix<double>& M = solved.M;
  cyclic::InterfaceOptions rio = io;
  rio.left_nodes = left_ids;
  rio.right_nodes = right_ids;
  const cyclic::CyclicSector sector(dofs, cyclic::find_interfaces(dofs, rio));

  // Nodal diameters and engine orders k = +-h (mod N).
  std::vector<int> nds = s.nodal_diameters;
  if (nds.empty() && !s.engine_orders.empty()) {
    std::set<int> from_orders;
    for (int k : s.engine_orders) from_orders.insert(std::min(k % N, N - k % N));
    nds.assign(from_orders.begin(), from_orders.end());
  }
  if (nds.empty())
    for (int h = 0; h <= N / 2; ++h) nds.push_back(h);
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
    throw InputError(where, key_of(model, name, "engine_orders"),
                     "at least one engine order of a listed nodal diameter", "none");

  // Tooth-force harmonics from the gear pair, exactly as mesh_harmonics computes them.
  const std::string force_note =
      !s.pair.empty()
          ? tooth_force_harmonics(model, name, s, orders, progress)
          : fmt::format("Harmonic forces given (force_amplitude), {} at every speed of the range.",
                        s.force_direction ? "along force_direction" : "tangential (-e_theta)");

  // Modes per nodal diameter, once.
  cyclic::CyclicModesOptions mo;
  mo.nodal_diameters = nds;
  // A sector has only so many modes per nodal diameter: asking more gives all of them.
  mo.eigen.n_modes = static_cast<int>(std::min<Eigen::Index>(s.n_modes, sector.num_reduced_dofs()));
  cyclic::CyclicModesResult modes = cyclic::solve_cyclic_modes(K, M, sector, mo, progress);
  if (modes.status != Status::Ok) throw NumericalError(name, modes.message);
  out.notes.push_back(modes.brief_report());

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
    for (const auto& f : orders)
      fs.excitations.push_back(
          {f.nodal_diameter, f.engine_order, order_loads(c, points, s, f, scale)});
    return response::run_cyclic_forced_response(sector, modes.diameters, fs, cb ? &*cb : nullptr,
                                                progress);
  };
  response::CyclicForcedResult result = run(1.0);

  const std::vector<double> rpm = [&] {
    std::vector<double> v;
    for (double w : s.speeds) v.push_back(w * kRpm);
    return v;
  }();

  // The harmonic forces used.
  std::vector<double> force_used(orders.size());
  {
    Table t;
    t.name = "harmonic_forces";
    t.title =
        "Harmonic forces per nodal diameter and engine order (one-sided amplitudes; radial and "
        "axial signed relative to the tangential phase, gear/tooth_forces.hpp signs)";
    std::vector<double> nd, eo, ft, fr, fa, phase, total;
    std::vector<std::string> rule;
    for (std::size_t j = 0; j < orders.size(); ++j) {
      const OrderForce& f = orders[j];
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
      force_used[j] = total.back();
    }
    t.add("nodal_diameter", "", nd);
    t.add("engine_order", "", eo);
    t.add_text("order_rule", rule);
    t.add("tangential_n", "N", ft);
    t.add("radial_n", "N", fr);
    t.add("axial_n", "N", fa);
    t.add("phase_deg", "deg", phase);
    t.add("amplitude_n", "N", total);
    out.tables.push_back(std::move(t));
  }
  out.notes.push_back(force_note);

  // Comparison with a measured response (thesis sec. 5.2): peak speed, amplitude and Q.
  if (!s.measured_file.empty()) {
    const gear::MeasuredResponse m = read_measured(model, name, s.measured_file);
    const std::size_t sensor = measured_sensor_index(result.sensors, s.measured_sensor, where,
                                                     key_of(model, name, "measured_sensor"));
    int order_index = -1;
    if (s.measured_engine_order > 0) {
      for (std::size_t j = 0; j < orders.size(); ++j)
        if (orders[j].engine_order == s.measured_engine_order) order_index = static_cast<int>(j);
      if (order_index < 0)
        throw InputError(where, key_of(model, name, "measured_engine_order"),
                         "an engine order of this analysis (or 0: the superposed sum)",
                         std::to_string(s.measured_engine_order));
    }
    auto computed_curve = [&](const response::CyclicForcedResult& r) {
      std::vector<double> a(rpm.size());
      for (std::size_t i = 0; i < rpm.size(); ++i) {
        const auto row = static_cast<Eigen::Index>(i);
        const auto col = static_cast<Eigen::Index>(sensor);
        a[i] =
            order_index < 0
                ? r.amplitude_sum(row, col)
                : std::abs(r.orders[static_cast<std::size_t>(order_index)].displacement(row, col));
      }
      return a;
    };
    const std::vector<double> computed = computed_curve(result);
    const std::string curve_name =
        fmt::format("{} {}", result.sensors[sensor].name,
                    order_index < 0 ? std::string("sum of orders")
                                    : fmt::format("EO {}", s.measured_engine_order));
    MeasuredComparison mc =
        compare_with_measured(out, m, rpm, computed, curve_name, s.min_prominence_db);
    Plot& p = mc.plot;
    if (!mc.peaks.empty()) {
      const gear::PeakComparison& pc = mc.peaks[mc.main];
      if (s.scale_to_measured) {
        // Linear model: scaling every harmonic by A_measured / A_computed reproduces the
        // measured peak; the implied force is the scaled harmonic (thesis sec. 5.2).
        const double scale = pc.measured.amplitude / pc.computed.amplitude;
        std::vector<double> nd, eo, used;
        for (std::size_t j = 0; j < orders.size(); ++j) {
          if (order_index >= 0 && static_cast<int>(j) != order_index) continue;
          nd.push_back(orders[j].nodal_diameter);
          eo.push_back(orders[j].engine_order);
          used.push_back(force_used[j]);
        }
        out.tables.push_back(force_scaling_table(
            pc, "Harmonic forces", {{"nodal_diameter", nd}, {"engine_order", eo}}, used));
        result = run(scale);
        p.traces.push_back(curve("computed, scaled", rpm, computed_curve(result), "dash"));
        out.notes.push_back(fmt::format(
            "scale_to_measured: every harmonic force is multiplied by {:.6g} (table "
            "force_scaling); the response tables and plots below show the scaled response.",
            scale));
      }
    }
    out.plots.push_back(std::move(p));
  }

  // Tables and plots of the response.
  out.tables.insert(out.tables.begin(), result.resonance_table());
  out.tables.insert(out.tables.begin() + 1, s.superpose
                                                ? result.response_table()
                                                : without_superposition(result.response_table()));
  out.tables.push_back(result.peak_table());
  out.tables.push_back(modes.table());
  for (std::size_t j = 0; j < result.orders.size(); ++j) {
    const response::OrderResponse& o = result.orders[j];
    Plot p = amplitude_plot(
        fmt::format("response_h{}_k{}", o.nodal_diameter, o.engine_order),
        fmt::format("Response to engine order {} (ND {}, {} wave, k = {}) in the rotating frame",
                    o.engine_order, o.nodal_diameter, response::to_string(o.relation.wave),
                    o.relation.rule));
    for (std::size_t k = 0; k < result.sensors.size(); ++k) {
      std::vector<double> a(rpm.size());
      for (std::size_t i = 0; i < rpm.size(); ++i)
        a[i] = std::abs(o.displacement(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)));
      p.traces.push_back(curve(result.sensors[k].name, rpm, a));
    }
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

  // How far to trust it.
  const double w_max = s.speeds.back();
  for (const auto& d : modes.diameters) {
    int k_max = 0;
    for (const auto& f : orders)
      if (f.nodal_diameter == d.nodal_diameter) k_max = std::max(k_max, f.engine_order);
    if (k_max == 0 || d.frequency_hz.size() == 0) continue;
    const double f_top = d.frequency_hz[d.frequency_hz.size() - 1];
    const double f_exc = k_max * w_max / kTwoPi;
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
      c.name, N));
  if (!result.message.empty()) out.notes.push_back(result.message);
  out.status = result.status;
  if (result.status != Status::Ok) out.message = result.message;
  return out;
}

// ---------------------------------------------------------------------------------------------
// checks before the run

void check_forced_analyses(const model::Model& model, const assembly::SolidComponents& solids) {
  for (const model::Analysis& a : model.analyses) {
    if (const auto* s = a.settings_as<CyclicForcedResponseSettings>()) {
      auto it = solids.find(s->solid);
      if (it != solids.end()) (void)sector_points(model, a.name, it->second, *s);
      const auto* d = a.settings_as<DamperRingResponseSettings>();
      if (d != nullptr && it != solids.end())
        check_damper_ring_response(model, it->second, *d, a.name);
      if (!s->pair.empty()) {
        const analyses::PairModel pm =
            analyses::build_pair_model(model, analyses::pair_index(model, s->pair));
        const int teeth = s->gear == 1 ? pm.pair->teeth1 : pm.pair->teeth2;
        const double cr =
            std::isnan(s->contact_ratio) ? pm.geometry.total_contact_ratio : s->contact_ratio;
        try {
          (void)gear::tooth_load_window(0.0, teeth, cr);
        } catch (const InputError& e) {
          throw InputError(a.where, key_of(model, a.name, "contact_ratio"), e.expected(), e.found(),
                           e.hint());
        }
      }
      if (!s->measured_file.empty()) (void)read_measured(model, a.name, s->measured_file);
    }
    if (const auto* g = a.settings_as<GearForcedResponseSettings>()) {
      if (!g->measured_file.empty()) (void)read_measured(model, a.name, g->measured_file);
      if (!g->pair.empty()) {
        const analyses::PairModel pm =
            analyses::build_pair_model(model, analyses::pair_index(model, g->pair));
        try {
          (void)analyses::blocked_mesh_force_harmonics(pm, g->max_mesh_order);
        } catch (const InputError& e) {
          throw InputError(a.where, key_of(model, a.name, "max_mesh_order"),
                           "a mesh order below half the STE samples per mesh cycle", e.found(),
                           "give more samples per cycle (the pair's ste_samples)");
        }
      }
    }
  }
}

}  // namespace geardyn::analyses
