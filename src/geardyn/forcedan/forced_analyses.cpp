#include "geardyn/forcedan/forced_analyses.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/version.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/forced/cyclic_forced_response.hpp"
#include "geardyn/forced/rotor_mesh_response.hpp"
#include "geardyn/forcedan/damper_analysis.hpp"
#include "geardyn/forcedan/sector_excitation.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/gearan/pair_model.hpp"
#include "geardyn/gearan/tooth_force.hpp"
#include "geardyn/reduce/craig_bampton.hpp"

namespace geardyn::forcedan {

namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRpm = 60.0 / kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / std::numbers::pi;

/// The measured curve of a cyclic forced response: a displacement amplitude over speed.
gear::MeasuredResponse read_measured(const model::Model& model, const std::string& name,
                                     const std::string& file) {
  gear::MeasuredResponse m =
      gear::read_measured_response_csv(gearan::resolve_model_path(model, file));
  if (m.abscissa != gear::ResponseAbscissa::SpeedRpm || m.amplitude_unit != "m")
    throw InputError(
        where_of(model, name), key_of(model, name, "measured_file"),
        "a measured displacement over speed: columns speed_rpm and amplitude_m "
        "(or _mm, _um, _nm), like the computed response",
        fmt::format("'{}' with {} and an amplitude in {}", m.source,
                    m.abscissa == gear::ResponseAbscissa::SpeedRpm ? "speed_rpm" : "frequency_hz",
                    m.amplitude_unit));
  return m;
}

/// Index of the sensor a measured curve is compared with: `wanted` by name, or the first one.
/// InputError at `key` when no sensor has that name.
template <class Sensor>
std::size_t measured_sensor_index(const std::vector<Sensor>& sensors, const std::string& wanted,
                                  const SourceLocation& where, const std::string& key) {
  if (wanted.empty()) return 0;
  auto it =
      std::find_if(sensors.begin(), sensors.end(), [&](const auto& x) { return x.name == wanted; });
  if (it == sensors.end()) {
    std::string names;
    for (const auto& x : sensors) names += (names.empty() ? "" : ", ") + x.name;
    throw InputError(where, key, fmt::format("a sensor of this analysis ({})", names),
                     fmt::format("\"{}\"", wanted));
  }
  return static_cast<std::size_t>(it - sensors.begin());
}

/// The comparison of a computed response over speed with a measured one, shared by the forced
/// responses (thesis sec. 5.2): the overlay plot (measured markers, computed line; the caller may
/// add traces before pushing it), the peak table and a note on the largest measured peak.
struct MeasuredComparison {
  Plot plot;
  std::vector<gear::PeakComparison> peaks;  ///< empty: no prominent measured peak
  std::size_t main = 0;                     ///< the largest measured peak
};

/// Table "force_scaling": each harmonic force used and the force that makes the computed peak
/// `pc` match the measured one (linear model: both scale by A_measured / A_computed). `ids` are
/// the leading columns naming each row (nodal diameter and engine order, or mesh order).
Table force_scaling_table(const gear::PeakComparison& pc, const std::string& what,
                          const std::vector<std::pair<std::string, std::vector<double>>>& ids,
                          const std::vector<double>& used) {
  Table f;
  f.name = "force_scaling";
  f.title = fmt::format("{} that make the computed peak match the measured one (scale {:.6g})",
                        what, pc.measured.amplitude / pc.computed.amplitude);
  std::vector<double> implied, sc;
  for (double u : used) {
    const gear::ForceScaling fsc = gear::scale_force_to_peak(pc, u);
    implied.push_back(fsc.implied_force_n);
    sc.push_back(fsc.scale);
  }
  for (const auto& [column, values] : ids) f.add(column, "", values);
  f.add("force_used_n", "N", used);
  f.add("implied_force_n", "N", implied);
  f.add("scale", "", sc);
  return f;
}

MeasuredComparison compare_with_measured(AnalysisOutput& out, const gear::MeasuredResponse& m,
                                         const std::vector<double>& rpm,
                                         const std::vector<double>& computed,
                                         const std::string& curve_name, double min_prominence_db) {
  MeasuredComparison c;
  gear::CorrelationOptions co;
  co.min_prominence_db = min_prominence_db;
  c.peaks = gear::compare_peaks(m.x, m.amplitude, rpm, computed, co);
  c.plot.name = "measured_overlay";
  c.plot.title = fmt::format("Measured response ({}) and the computed {}", m.source, curve_name);
  c.plot.x_label = "speed [rpm]";
  c.plot.y_label = "amplitude [m]";
  c.plot.y_log = true;
  Trace mt = curve("measured", m.x, m.amplitude);
  mt.mode = Trace::Mode::Markers;
  c.plot.traces.push_back(std::move(mt));
  c.plot.traces.push_back(curve("computed", rpm, computed));
  if (c.peaks.empty()) {
    out.notes.push_back(fmt::format(
        "Measured file {}: no peak with a prominence of {:.3g} dB; nothing compared (lower "
        "min_prominence_db or measure across the resonance).",
        m.source, min_prominence_db));
    return c;
  }
  Table t = gear::correlation_table(c.peaks, gear::ResponseAbscissa::SpeedRpm, "m", "comparison");
  t.title = fmt::format(
      "Measured versus computed peaks ({}); mismatch = (computed - measured) / measured",
      curve_name);
  out.tables.push_back(std::move(t));
  for (std::size_t j = 1; j < c.peaks.size(); ++j)
    if (c.peaks[j].measured.amplitude > c.peaks[c.main].measured.amplitude) c.main = j;
  const gear::PeakComparison& pc = c.peaks[c.main];
  out.notes.push_back(
      fmt::format("Largest measured peak at {:.6g} rpm, {:.4g} m, Q = {:.4g}; computed {:.6g} rpm, "
                  "{:.4g} m, Q = {:.4g}: speed {:+.2f} %, amplitude {:+.1f} %, Q {:+.1f} %.",
                  pc.measured.x, pc.measured.amplitude, pc.measured.q_factor, pc.computed.x,
                  pc.computed.amplitude, pc.computed.q_factor, 100 * pc.x_mismatch,
                  100 * pc.amplitude_mismatch, 100 * pc.q_mismatch));
  return c;
}

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

// ---------------------------------------------------------------------------------------------
// cyclic_forced_response

AnalysisOutput run_cyclic_forced_response(const model::Model& model,
                                          const component::SolidComponent& c,
                                          const model::CyclicForcedResponseSettings& s,
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
      f.amplitude = forced::kNaN;
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

  forced::CyclicForcedSettings fs;
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
    return forced::run_cyclic_forced_response(sector, modes.diameters, fs, cb ? &*cb : nullptr,
                                              progress);
  };
  forced::CyclicForcedResult result = run(1.0);

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
      rule.push_back(forced::relate_order(N, f.nodal_diameter, f.engine_order).rule);
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
        ft.push_back(s.force_direction ? forced::kNaN : f.amplitude);
        fr.push_back(s.force_direction ? forced::kNaN : 0.0);
        fa.push_back(s.force_direction ? forced::kNaN : 0.0);
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
    auto computed_curve = [&](const forced::CyclicForcedResult& r) {
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
    const forced::OrderResponse& o = result.orders[j];
    Plot p = amplitude_plot(
        fmt::format("response_h{}_k{}", o.nodal_diameter, o.engine_order),
        fmt::format("Response to engine order {} (ND {}, {} wave, k = {}) in the rotating frame",
                    o.engine_order, o.nodal_diameter, forced::to_string(o.relation.wave),
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
// gear_forced_response

AnalysisOutput run_gear_forced_response(const model::Model& model, const fe::LinearSystem& system,
                                        const model::GearForcedResponseSettings& s,
                                        const std::string& name, Progress& progress) {
  forced::RotorForcedSettings rs;
  rs.gear_mesh = s.gear_mesh.empty() ? model.gear_meshes.front().name : s.gear_mesh;
  std::string force_note;
  if (!s.pair.empty()) {
    const gearan::PairModel pm = gearan::build_pair_model(model, gearan::pair_index(model, s.pair));
    const std::vector<Complex> f = gearan::blocked_mesh_force_harmonics(pm, s.max_mesh_order);
    for (int p = 1; p <= s.max_mesh_order; ++p)
      rs.harmonics.push_back({p, f[static_cast<std::size_t>(p - 1)]});
    force_note = fmt::format(
        "Mesh-order forces from pair '{}': harmonics of the infinite-inertia mesh force F_s k(t) "
        "/ k_mean (F_s = {:.6g} N, {} STE), i.e. the blocked force k_mean e_p of the "
        "transmission error to first order; the rotor model carries the mesh stiffness itself, "
        "so its own dynamics shape the response (the pair's dynamic model is not used, it would "
        "count the mesh resonance twice).",
        s.pair, pm.static_force_n, pm.ste_from_file ? "file" : "synthetic ISO 6336");
  } else {
    for (int p = 1; p <= s.max_mesh_order; ++p)
      rs.harmonics.push_back({p, Complex(s.force_amplitude.size() == 1
                                             ? s.force_amplitude[0]
                                             : s.force_amplitude[static_cast<std::size_t>(p - 1)],
                                         0.0)});
    force_note = "Mesh-order forces given (force_amplitude), along the line of action.";
  }
  rs.sensors = forced::rotor_sensors(model, system, s.sensors);
  rs.speeds = Eigen::Map<const Eigen::VectorXd>(s.speeds.data(),
                                                static_cast<Eigen::Index>(s.speeds.size()));
  rs.method = forced::RotorForcedMethod::ModalReduced;
  rs.n_modes = s.n_modes;
  rs.residual_vectors = s.residual_vectors;
  const forced::RotorForcedResult r = forced::run_mesh_forced_response(model, system, rs, progress);
  if (r.displacement.size() != r.harmonics.size())
    throw NumericalError(name,
                         fmt::format("the mesh-order response was not computed: {}", r.message));

  AnalysisOutput out;
  out.tables.push_back(r.resonance_table());
  out.tables.push_back(r.response_table());
  {
    Table t;
    t.name = "mesh_order_forces";
    t.title = "Harmonic mesh forces along the line of action per mesh order";
    std::vector<double> order, amp, phase, per_speed;
    for (const auto& h : r.harmonics) {
      order.push_back(h.order);
      amp.push_back(std::abs(h.amplitude));
      phase.push_back(std::arg(h.amplitude) * kDeg);
      per_speed.push_back(h.order * r.mesh_frequency_per_speed);
    }
    t.add("mesh_order", "", order);
    t.add("amplitude_n", "N", amp);
    t.add("phase_deg", "deg", phase);
    t.add("frequency_per_speed", "", per_speed);
    out.tables.push_back(std::move(t));
  }
  std::vector<double> rpm;
  for (double w : s.speeds) rpm.push_back(w * kRpm);
  for (std::size_t j = 0; j < r.harmonics.size(); ++j) {
    Plot p = amplitude_plot(
        fmt::format("response_p{}", r.harmonics[j].order),
        fmt::format("Response to mesh order {} of '{}'", r.harmonics[j].order, r.gear_mesh));
    for (std::size_t k = 0; k < r.sensors.size(); ++k) {
      std::vector<double> a(rpm.size());
      for (std::size_t i = 0; i < rpm.size(); ++i)
        a[i] =
            std::abs(r.displacement[j](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)));
      p.traces.push_back(curve(r.sensors[k].name, rpm, a));
    }
    out.plots.push_back(std::move(p));
  }
  if (r.harmonics.size() > 1) {
    Plot p = amplitude_plot("superposed", "All mesh orders: sum of amplitudes and RMS");
    for (std::size_t k = 0; k < r.sensors.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      std::vector<double> sum(rpm.size()), rms(rpm.size());
      for (std::size_t i = 0; i < rpm.size(); ++i) {
        sum[i] = r.amplitude_sum(static_cast<Eigen::Index>(i), col);
        rms[i] = r.amplitude_rms(static_cast<Eigen::Index>(i), col);
      }
      p.traces.push_back(curve(r.sensors[k].name + " sum", rpm, sum));
      p.traces.push_back(curve(r.sensors[k].name + " RMS", rpm, rms, "dot"));
    }
    out.plots.push_back(std::move(p));
  }
  // Comparison with a measured response: the sum of the mesh orders or one order at a sensor.
  if (!s.measured_file.empty()) {
    const gear::MeasuredResponse m = read_measured(model, name, s.measured_file);
    const std::size_t sensor =
        measured_sensor_index(r.sensors, s.measured_sensor, where_of(model, name),
                              key_of(model, name, "measured_sensor"));
    int order_index = -1;  // the parser keeps measured_mesh_order within 0 .. max_mesh_order
    for (std::size_t j = 0; j < r.harmonics.size(); ++j)
      if (r.harmonics[j].order == s.measured_mesh_order) order_index = static_cast<int>(j);
    std::vector<double> computed(rpm.size());
    for (std::size_t i = 0; i < rpm.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i), col = static_cast<Eigen::Index>(sensor);
      computed[i] = order_index < 0
                        ? r.amplitude_sum(row, col)
                        : std::abs(r.displacement[static_cast<std::size_t>(order_index)](row, col));
    }
    const std::string curve_name =
        fmt::format("{} {}", r.sensors[sensor].name,
                    order_index < 0 ? std::string("sum of mesh orders")
                                    : fmt::format("mesh order {}", s.measured_mesh_order));
    MeasuredComparison mc =
        compare_with_measured(out, m, rpm, computed, curve_name, s.min_prominence_db);
    if (!mc.peaks.empty() && s.scale_to_measured) {
      // Linear model: the forces scaled by A_measured / A_computed reproduce the measured peak,
      // and the response scales with them.
      const gear::PeakComparison& pc = mc.peaks[mc.main];
      const double scale = pc.measured.amplitude / pc.computed.amplitude;
      std::vector<double> order, used;
      for (std::size_t j = 0; j < r.harmonics.size(); ++j) {
        if (order_index >= 0 && static_cast<int>(j) != order_index) continue;
        order.push_back(r.harmonics[j].order);
        used.push_back(std::abs(r.harmonics[j].amplitude));
      }
      out.tables.push_back(force_scaling_table(pc, "Mesh forces", {{"mesh_order", order}}, used));
      std::vector<double> scaled = computed;
      for (double& v : scaled) v *= scale;
      mc.plot.traces.push_back(curve("computed, scaled", rpm, scaled, "dash"));
      out.notes.push_back(fmt::format(
          "scale_to_measured: the mesh forces multiplied by {:.6g} (table force_scaling) "
          "reproduce the measured peak; the response tables and the other plots are unscaled.",
          scale));
    }
    out.plots.push_back(std::move(mc.plot));
  }
  out.notes.push_back(r.brief_report());
  out.notes.push_back(force_note);
  const double f_exc = s.max_mesh_order * r.mesh_frequency_per_speed * s.speeds.back() / kTwoPi;
  out.notes.push_back(fmt::format(
      "Modal basis: {} vectors ({} modes at zero speed up to {:.6g} Hz{}); the highest "
      "excitation frequency is {:.6g} Hz (mesh order {} at {:.6g} rpm){}",
      r.basis_size, std::min(s.n_modes, r.basis_size), r.highest_mode_hz,
      s.residual_vectors ? ", plus the static residual vector" : "", f_exc, s.max_mesh_order,
      s.speeds.back() * kRpm,
      f_exc > 0.8 * r.highest_mode_hz
          ? ": it reaches beyond the basis, so resonances of higher modes are missing; raise "
            "n_modes."
          : "."));
  out.notes.push_back(
      "Damping: the model's [damping] (Rayleigh, modal, structural) and element damping; "
      "gyroscopic and speed-dependent bearing terms are included per speed in the reduced "
      "matrices.");
  out.status = r.status;
  if (r.status != Status::Ok) out.message = r.message;
  return out;
}

// ---------------------------------------------------------------------------------------------
// checks before the run

void check_forced_analyses(const model::Model& model, const component::SolidComponents& solids) {
  for (const model::Analysis& a : model.analyses) {
    if (const auto* s = model::settings_as<model::CyclicForcedResponseSettings>(a)) {
      auto it = solids.find(s->solid);
      if (it != solids.end()) (void)sector_points(model, a.name, it->second, *s);
      const auto* d = std::get_if<model::DamperRingResponseSettings>(&a.settings);
      if (d != nullptr && it != solids.end())
        check_damper_ring_response(model, it->second, *d, a.name);
      if (!s->pair.empty()) {
        const gearan::PairModel pm =
            gearan::build_pair_model(model, gearan::pair_index(model, s->pair));
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
    if (const auto* g = std::get_if<model::GearForcedResponseSettings>(&a.settings)) {
      if (!g->measured_file.empty()) (void)read_measured(model, a.name, g->measured_file);
      if (!g->pair.empty()) {
        const gearan::PairModel pm =
            gearan::build_pair_model(model, gearan::pair_index(model, g->pair));
        try {
          (void)gearan::blocked_mesh_force_harmonics(pm, g->max_mesh_order);
        } catch (const InputError& e) {
          throw InputError(a.where, key_of(model, a.name, "max_mesh_order"),
                           "a mesh order below half the STE samples per mesh cycle", e.found(),
                           "give more samples per cycle (the pair's ste_samples)");
        }
      }
    }
  }
}

}  // namespace geardyn::forcedan
