#include "geardyn/analyses/gear_forced_response.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "geardyn/analyses/cyclic_forced_response.hpp"  // the settings sector_excitation.hpp uses
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRpm = 60.0 / kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / std::numbers::pi;

}  // namespace

AnalysisOutput run_gear_forced_response(const model::Model& model, const fe::LinearSystem& system,
                                        const GearForcedResponseSettings& s,
                                        const std::string& name, Progress& progress) {
  response::RotorForcedSettings rs;
  rs.gear_mesh = s.gear_mesh.empty() ? model.gear_meshes.front().name : s.gear_mesh;
  std::string force_note;
  if (!s.pair.empty()) {
    const analyses::PairModel pm =
        analyses::build_pair_model(model, analyses::pair_index(model, s.pair));
    const std::vector<Complex> f = analyses::blocked_mesh_force_harmonics(pm, s.max_mesh_order);
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
  rs.sensors = response::rotor_sensors(model, system, s.sensors);
  rs.speeds = Eigen::Map<const Eigen::VectorXd>(s.speeds.data(),
                                                static_cast<Eigen::Index>(s.speeds.size()));
  rs.method = response::RotorForcedMethod::ModalReduced;
  rs.n_modes = s.n_modes;
  rs.residual_vectors = s.residual_vectors;
  const response::RotorForcedResult r =
      response::run_mesh_forced_response(model, system, rs, progress);
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

}  // namespace geardyn::analyses
