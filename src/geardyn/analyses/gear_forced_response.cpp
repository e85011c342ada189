#include "geardyn/analyses/gear_forced_response.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "geardyn/analyses/cyclic_forced_response.hpp"  // the settings sector_excitation.hpp uses
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/correlation.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;
constexpr double kRpm = 60.0 / units::kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / units::kPi;

/// The sensors of the analysis: an unknown name is an InputError at its `sensors` key.
void check_sensor_names(const model::Model& model, const std::vector<std::string>& names,
                        const Context& context) {
  for (const std::string& name : names)
    if (std::none_of(model.sensors.begin(), model.sensors.end(),
                     [&](const model::Sensor& s) { return s.name == name; }))
      throw context.error("sensors", "the name of a sensor of the model",
                          fmt::format("'{}'", name));
}

/// Amplitude of mesh order j (or of the sum, j < 0) at sensor `k` over speed.
std::vector<double> order_curve(const response::RotorForcedResult& r, int j, std::size_t k) {
  std::vector<double> a(static_cast<std::size_t>(r.speeds.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i), col = static_cast<Eigen::Index>(k);
    a[i] = j < 0 ? r.amplitude_sum(row, col)
                 : std::abs(r.displacement[static_cast<std::size_t>(j)](row, col));
  }
  return a;
}

Table mesh_order_forces_table(const response::RotorForcedResult& r) {
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
  return t;
}

void add_response_plots(AnalysisOutput& out, const response::RotorForcedResult& r,
                        const std::vector<double>& rpm) {
  for (std::size_t j = 0; j < r.harmonics.size(); ++j) {
    Plot p = amplitude_plot(
        fmt::format("response_p{}", r.harmonics[j].order),
        fmt::format("Response to mesh order {} of '{}'", r.harmonics[j].order, r.gear_mesh));
    for (std::size_t k = 0; k < r.sensors.size(); ++k)
      p.traces.push_back(curve(r.sensors[k].name, rpm, order_curve(r, static_cast<int>(j), k)));
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
}

// Comparison with a measured response: the sum of the mesh orders or one order at a sensor.
void add_measured_comparison(AnalysisOutput& out, const model::Model& model,
                             const GearForcedResponseSettings& s,
                             const response::RotorForcedResult& r, const std::vector<double>& rpm,
                             const Context& context) {
  const gear::MeasuredResponse m = read_measured(model, context, s.measured_file);
  const std::size_t sensor = measured_sensor_index(r.sensors, s.measured_sensor, context);
  int order_index = -1;  // the parser keeps measured_mesh_order within 0 .. max_mesh_order
  for (std::size_t j = 0; j < r.harmonics.size(); ++j)
    if (r.harmonics[j].order == s.measured_mesh_order) order_index = static_cast<int>(j);
  const std::vector<double> computed = order_curve(r, order_index, sensor);
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

std::string force_note(const GearForcedResponseSettings& s, const GearForcedResponseResult& g) {
  if (!g.from_pair) return "Mesh-order forces given (force_amplitude), along the line of action.";
  return fmt::format(
      "Mesh-order forces from pair '{}': harmonics of the infinite-inertia mesh force F_s k(t) "
      "/ k_mean (F_s = {:.6g} N, STE: {}), i.e. the blocked force k_mean e_p of the "
      "transmission error to first order; the rotor model carries the mesh stiffness itself, "
      "so its own dynamics shape the response (the pair's dynamic model is not used, it would "
      "count the mesh resonance twice).",
      s.pair, g.pair_static_force_n, g.pair_ste_source);
}

}  // namespace

double GearForcedResponseResult::peak_amplitude(std::size_t sensor) const {
  const std::vector<double> a = order_curve(response, -1, sensor);
  return a[largest_sample(a)];
}

std::size_t GearForcedResponseResult::sensor_index(const std::string& name) const {
  return requested_sensor(response.sensors, name);
}

GearForcedResponseResult run_gear_forced_response(const model::Model& model,
                                                  const GearForcedResponseSettings& s,
                                                  const Context& context) {
  const fe::LinearSystem& system = context.system();
  GearForcedResponseResult g;
  response::RotorForcedSettings rs;
  rs.gear_mesh = s.gear_mesh.empty() ? model.gear_meshes.front().name : s.gear_mesh;
  if (!s.pair.empty()) {
    const analyses::PairModel pm =
        analyses::build_pair_model(model, analyses::pair_index(model, s.pair));
    const std::vector<Complex> f = analyses::blocked_mesh_force_harmonics(pm, s.max_mesh_order);
    for (int p = 1; p <= s.max_mesh_order; ++p)
      rs.harmonics.push_back({p, f[static_cast<std::size_t>(p - 1)]});
    g.from_pair = true;
    g.pair_static_force_n = pm.static_force_n;
    g.pair_ste_source = pm.ste_source_label();
  } else {
    for (int p = 1; p <= s.max_mesh_order; ++p)
      rs.harmonics.push_back({p, Complex(s.force_amplitude.size() == 1
                                             ? s.force_amplitude[0]
                                             : s.force_amplitude[static_cast<std::size_t>(p - 1)],
                                         0.0)});
  }
  check_sensor_names(model, s.sensors, context);
  rs.sensors = response::rotor_sensors(model, system, s.sensors);
  rs.speeds = Eigen::Map<const Eigen::VectorXd>(s.speeds.data(),
                                                static_cast<Eigen::Index>(s.speeds.size()));
  rs.method = response::RotorForcedMethod::ModalReduced;
  rs.n_modes = s.n_modes;
  rs.residual_vectors = s.residual_vectors;
  g.response = response::run_mesh_forced_response(model, system, rs, context.progress());
  if (g.response.displacement.size() != g.response.harmonics.size())
    throw NumericalError(context.name(), fmt::format("the mesh-order response was not computed: {}",
                                                     g.response.message));
  return g;
}

AnalysisOutput gear_forced_response_output(const model::Model& model,
                                           const GearForcedResponseSettings& s,
                                           const GearForcedResponseResult& g,
                                           const Context& context) {
  const response::RotorForcedResult& r = g.response;
  AnalysisOutput out;
  out.tables.push_back(r.resonance_table());
  out.tables.push_back(r.response_table());
  out.tables.push_back(mesh_order_forces_table(r));
  std::vector<double> rpm;
  for (double w : s.speeds) rpm.push_back(w * kRpm);
  add_response_plots(out, r, rpm);
  if (!s.measured_file.empty()) add_measured_comparison(out, model, s, r, rpm, context);
  out.notes.push_back(r.brief_report());
  out.notes.push_back(force_note(s, g));
  const double f_exc =
      s.max_mesh_order * r.mesh_frequency_per_speed * s.speeds.back() / units::kTwoPi;
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

void check_gear_forced_response_inputs(const model::Model& model,
                                       const GearForcedResponseSettings& g,
                                       const Context& context) {
  if (!g.measured_file.empty()) (void)read_measured(model, context, g.measured_file);
  if (g.pair.empty()) return;
  const PairModel pm = build_pair_model(model, pair_index(model, g.pair));
  try {
    (void)blocked_mesh_force_harmonics(pm, g.max_mesh_order);
  } catch (const InputError& e) {
    throw context.error("max_mesh_order", "a mesh order below half the STE samples per mesh cycle",
                        e.found(), "give more samples per cycle (the pair's ste_samples)");
  }
}

}  // namespace geardyn::analyses
