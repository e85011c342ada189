// The tables, plots, files and notes of the gear_whine analysis.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/analyses/gear_whine.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/meshio/vtu_writer.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kRpm = 60.0 / units::kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / units::kPi;

std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c) {
  return std::vector<double>(m.col(c).data(), m.col(c).data() + m.rows());
}

std::string accel_unit(const response::RotorSensor& s) {
  return s.rotational ? "rad/s^2" : "m/s^2";
}
std::string accel_suffix(const response::RotorSensor& s) {
  return s.rotational ? "rad_s2" : "m_s2";
}

/// dB of an RMS acceleration re `ref` (ISO 1683: 1e-6 m/s^2).
double level_db(double rms, double ref) { return 20.0 * std::log10(std::max(rms, 1e-300) / ref); }

/// Sound power level and sound pressure level of the 0-order radiator at each speed [dB].
std::pair<std::vector<double>, std::vector<double>> radiator_levels(const WhineRadiation& w,
                                                                    const GearWhineSettings& s) {
  std::vector<double> lw, lp;
  for (Eigen::Index i = 0; i < w.radiator_total_w.size(); ++i) {
    lw.push_back(acoustics::sound_power_level_db(w.radiator_total_w[i]));
    lp.push_back(
        acoustics::sound_pressure_level_db(w.radiator_total_w[i], s.distance, s.directivity));
  }
  return {lw, lp};
}

Table te_table(const GearWhineResult& g) {
  Table t;
  t.name = "te_orders";
  t.title = "Transmission error and mesh force per mesh order (0-peak and peak-to-peak)";
  std::vector<double> order, e0, epp, phase, force, fphase;
  for (std::size_t j = 0; j < g.te_amplitude_m.size(); ++j) {
    order.push_back(g.response.harmonics[j].order);
    e0.push_back(g.te_amplitude_m[j] * 1e6);
    epp.push_back(2.0 * g.te_amplitude_m[j] * 1e6);
    phase.push_back(g.te_phase_rad[j] * kDeg);
    force.push_back(std::abs(g.response.harmonics[j].amplitude));
    fphase.push_back(std::arg(g.response.harmonics[j].amplitude) * kDeg);
  }
  t.add("mesh_order", "", order);
  t.add("te_0peak_um", "um", e0);
  t.add("te_peak_peak_um", "um", epp);
  t.add("te_phase_deg", "deg", phase);
  t.add("force_amplitude_n", "N", force);
  t.add("force_phase_deg", "deg", fphase);
  return t;
}

Table acceleration_table(const GearWhineResult& g, const GearWhineSettings& s,
                         const std::vector<double>& rpm) {
  const response::RotorForcedResult& r = g.response;
  Table t;
  t.name = "whine_acceleration";
  t.title =
      fmt::format("Acceleration per mesh order of '{}' at the sensors over speed", r.gear_mesh);
  t.add("speed_rpm", "rpm", rpm);
  t.add("mesh_frequency_hz", "Hz", [&] {
    std::vector<double> f;
    for (double w : rpm) f.push_back(w / kRpm * r.mesh_frequency_per_speed / units::kTwoPi);
    return f;
  }());
  for (std::size_t h = 0; h < r.harmonics.size(); ++h)
    for (std::size_t k = 0; k < r.sensors.size(); ++k) {
      std::vector<double> amp, phase;
      for (Eigen::Index i = 0; i < r.speeds.size(); ++i) {
        const std::complex<double> a = g.acceleration[h](i, static_cast<Eigen::Index>(k));
        amp.push_back(std::abs(a));
        phase.push_back(std::arg(a) * kDeg);
      }
      const std::string base = fmt::format("{}_p{}", r.sensors[k].name, r.harmonics[h].order);
      t.add(base + "_acceleration_" + accel_suffix(r.sensors[k]), accel_unit(r.sensors[k]), amp);
      t.add(base + "_phase_deg", "deg", phase);
    }
  for (std::size_t k = 0; k < r.sensors.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    const std::string& n = r.sensors[k].name;
    t.add(n + "_sum_" + accel_suffix(r.sensors[k]), accel_unit(r.sensors[k]),
          column(g.acceleration_sum, c));
    t.add(n + "_rms_" + accel_suffix(r.sensors[k]), accel_unit(r.sensors[k]),
          column(g.acceleration_rms, c));
    std::vector<double> db;
    for (Eigen::Index i = 0; i < r.speeds.size(); ++i)
      db.push_back(level_db(g.acceleration_rms(i, c), s.acceleration_reference));
    t.add(n + "_level_db", "dB", db);
  }
  return t;
}

Table resonance_table(const GearWhineResult& g) {
  const response::RotorForcedResult& r = g.response;
  std::vector<PeakRow> rows;
  for (const response::SpeedPeak& p : g.acceleration_peaks) {
    const response::RotorSensor& sensor = r.sensors[static_cast<std::size_t>(p.sensor)];
    PeakRow row;
    row.sensor = sensor.name;
    row.curve = p.curve < 0
                    ? std::string("sum")
                    : fmt::format("order {}", r.harmonics[static_cast<std::size_t>(p.curve)].order);
    row.location = p.speed * kRpm;
    row.amplitude = p.amplitude;
    row.amplitude_unit = accel_unit(sensor);
    row.half_power_low = p.speed1 * kRpm;
    row.half_power_high = p.speed2 * kRpm;
    row.q_factor = p.q_factor;
    row.points_in_band = p.points_in_band;
    row.resolved = p.resolved;
    rows.push_back(std::move(row));
  }
  return peak_table("whine_resonances",
                    "Resonance peaks of the acceleration per mesh order (curve: the order, or "
                    "the sum over orders); the excitation frequency is order x mesh frequency",
                    speed_axis(), rows);
}

Table radiation_table(const GearWhineResult& g, const GearWhineSettings& s,
                      const std::vector<double>& rpm) {
  const WhineRadiation& w = g.radiation;
  Table t;
  t.name = "radiated_power";
  t.title = fmt::format(
      "Radiated sound power of '{}' over speed (ERP with sigma = {:g}; 0-order "
      "radiator of radius {:.4g} m); levels re 1e-12 W and 2e-5 Pa",
      w.solid, s.radiation_efficiency, w.radiator_radius_m);
  t.add("speed_rpm", "rpm", rpm);
  for (std::size_t j = 0; j < g.response.harmonics.size(); ++j) {
    const int p = g.response.harmonics[j].order;
    const auto c = static_cast<Eigen::Index>(j);
    t.add(fmt::format("erp_p{}_w", p), "W", column(w.erp_w, c));
    t.add(fmt::format("mean_normal_velocity_p{}_m_s", p), "m/s", column(w.mean_velocity_ms, c));
  }
  const auto vec = [](const Eigen::VectorXd& v) {
    return std::vector<double>(v.data(), v.data() + v.size());
  };
  t.add("erp_w", "W", vec(w.erp_total_w));
  t.add("erp_level_db", "dB", vec(g.sound_power_level_db()));
  t.add("radiator_w", "W", vec(w.radiator_total_w));
  const auto [lw_rad, lp_rad] = radiator_levels(w, s);
  t.add("radiator_level_db", "dB", lw_rad);
  t.add("spl_erp_db", "dB", vec(g.sound_pressure_level_db(s)));
  t.add("spl_radiator_db", "dB", lp_rad);
  return t;
}

void add_plots(AnalysisOutput& out, const GearWhineResult& g, const GearWhineSettings& s,
               const std::vector<double>& rpm) {
  const response::RotorForcedResult& r = g.response;
  for (std::size_t k = 0; k < r.sensors.size(); ++k) {
    Plot p = amplitude_plot(fmt::format("acceleration_{}", k),
                            fmt::format("Acceleration at '{}' per mesh order", r.sensors[k].name));
    p.y_label = fmt::format("acceleration amplitude [{}]", accel_unit(r.sensors[k]));
    for (std::size_t h = 0; h < r.harmonics.size(); ++h) {
      std::vector<double> a;
      for (Eigen::Index i = 0; i < r.speeds.size(); ++i)
        a.push_back(std::abs(g.acceleration[h](i, static_cast<Eigen::Index>(k))));
      p.traces.push_back(curve(fmt::format("order {}", r.harmonics[h].order), rpm, a));
    }
    p.traces.push_back(curve("sum of orders", rpm,
                             column(g.acceleration_sum, static_cast<Eigen::Index>(k)), "dash"));
    out.plots.push_back(std::move(p));
  }
  if (!g.has_radiation) return;
  const WhineRadiation& w = g.radiation;
  Plot p;
  p.name = "sound_power";
  p.title = fmt::format("Sound power of '{}' and sound pressure at {:g} m", w.solid, s.distance);
  p.x_label = "speed [rpm]";
  p.y_label = "level [dB re 1e-12 W / 2e-5 Pa]";
  const Eigen::VectorXd lw = g.sound_power_level_db(), lp = g.sound_pressure_level_db(s);
  const auto [rad, rad_p] = radiator_levels(w, s);
  p.traces.push_back(
      curve("L_W from ERP", rpm, std::vector<double>(lw.data(), lw.data() + lw.size())));
  p.traces.push_back(curve("L_W 0-order radiator", rpm, rad, "dash"));
  p.traces.push_back(
      curve("L_p from ERP", rpm, std::vector<double>(lp.data(), lp.data() + lp.size()), "dot"));
  p.traces.push_back(curve("L_p 0-order radiator", rpm, rad_p, "dot"));
  p.y_log = false;
  out.plots.push_back(std::move(p));
}

void add_face_maps(AnalysisOutput& out, const model::Model& model, const GearWhineResult& g,
                   const Context& context) {
  const WhineRadiation& w = g.radiation;
  // The writer runs after the analysis, when a solid built on demand for a model variant is
  // gone: the files keep their own copy of the mesh.
  const auto mesh = std::make_shared<const solid::Mesh>(context.solid(model, w.solid).mesh);
  const acoustics::Surface& surface = w.surface;
  for (std::size_t m = 0; m < w.map_speeds.size(); ++m) {
    const double rpm = w.map_speeds[m] * kRpm;
    const Eigen::VectorXd& faces = w.face_erp_w[m];
    meshio::Field erp{"erp_w", 1, std::vector<double>(faces.data(), faces.data() + faces.size())};
    meshio::Field density{"erp_density_w_per_m2", 1, {}};
    for (std::size_t f = 0; f < surface.faces.size(); ++f)
      density.values.push_back(erp.values[f] / surface.faces[f].area);
    const std::string file = fmt::format("erp_faces_{:.0f}rpm.vtu", rpm);
    out.files.push_back(
        {file,
         fmt::format("ERP per face of '{}' at {:.0f} rpm (sum over the mesh orders), for ParaView",
                     w.solid, rpm),
         [mesh, surface, erp, density](const std::filesystem::path& path) {
           acoustics::write_surface_vtu(path, *mesh, surface, {erp, density}, {});
         }});
    acoustics::ErpDensityMap map = acoustics::erp_density_map(surface, faces, 50);
    Plot p;
    p.name = fmt::format("erp_map_{}", m);
    p.title = fmt::format(
        "ERP density on '{}' at {:.0f} rpm (faces projected on the plane of its "
        "two largest extents)",
        w.solid, rpm);
    p.x_label = map.x_label;
    p.y_label = map.y_label;
    p.equal_aspect = true;
    map.trace.name = "ERP density";
    map.trace.z_label = "ERP density [W/m^2]";
    p.traces.push_back(std::move(map.trace));
    out.plots.push_back(std::move(p));
  }
}

}  // namespace

AnalysisOutput gear_whine_output(const model::Model& model, const GearWhineSettings& s,
                                 const GearWhineResult& g, const Context& context) {
  const response::RotorForcedResult& r = g.response;
  AnalysisOutput out;
  std::vector<double> rpm;
  for (double w : s.speeds) rpm.push_back(w * kRpm);
  out.tables.push_back(te_table(g));
  out.tables.push_back(acceleration_table(g, s, rpm));
  out.tables.push_back(resonance_table(g));
  out.tables.push_back(r.response_table());
  if (g.has_radiation) out.tables.push_back(radiation_table(g, s, rpm));
  add_plots(out, g, s, rpm);
  if (g.has_radiation) add_face_maps(out, model, g, context);
  out.notes.push_back(r.brief_report());
  out.notes.push_back(fmt::format(
      "Excitation: the transmission error of pair '{}' ({}; peak-to-peak {:.4g} um over a mesh "
      "cycle) as the blocked mesh force F_s k(t) / k_mean (F_s = {:.6g} N), i.e. k_mean e_p at "
      "mesh order p to first order; the rotor model carries the mesh stiffness itself.",
      s.pair, g.ste_source, g.te_peak_to_peak_m * 1e6, g.static_force_n));
  const double f_exc =
      s.max_mesh_order * r.mesh_frequency_per_speed * s.speeds.back() / units::kTwoPi;
  out.notes.push_back(fmt::format(
      "Modal basis: {} vectors up to {:.6g} Hz; the highest excitation frequency is {:.6g} Hz{}",
      r.basis_size, r.highest_mode_hz, f_exc,
      f_exc > 0.8 * r.highest_mode_hz ? ": it reaches beyond the basis, so resonances of higher "
                                        "modes are missing; raise n_modes."
                                      : "."));
  out.notes.push_back(fmt::format(
      "Acceleration levels: 20 lg(a_rms / {:g} m/s^2) of the RMS over the mesh orders (ISO 1683 "
      "reference 1e-6 m/s^2 unless acceleration_reference is set).",
      s.acceleration_reference));
  if (g.has_radiation) {
    const WhineRadiation& w = g.radiation;
    out.notes.push_back(fmt::format(
        "Radiation of '{}' ({}: {} faces, {} nodes, {:.4g} m^2): ERP = 1/2 rho c sigma sum A "
        "|v_n|^2 "
        "(rho = {:g} kg/m^3, c = {:g} m/s, sigma = {:g}) is an upper bound of the radiated power "
        "above the coincidence frequency and overestimates it below; the 0-order radiator (radius "
        "{:.4g} m) is the power of a pulsating sphere with the surface's mean square normal "
        "velocity; "
        "orders add in power. L_p at {:g} m with directivity {:g}, free field.",
        w.solid, w.surface_set.empty() ? "whole exterior" : "set '" + w.surface_set + "'",
        w.surface_faces, w.surface_nodes, w.area_m2, s.air_density, s.speed_of_sound,
        s.radiation_efficiency, w.radiator_radius_m, s.distance, s.directivity));
  }
  out.status = r.status;
  if (r.status != Status::Ok) out.message = r.message;
  return out;
}

}  // namespace geardyn::analyses
