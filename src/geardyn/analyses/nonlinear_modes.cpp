#include "geardyn/analyses/nonlinear_modes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/analyses/nonlinear_elements.hpp"
#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/nonlinear_modes.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kHz = 1.0 / units::kTwoPi;

std::string unit_of(const NonlinearModesResult& r, std::size_t s) {
  return r.sensor_rotational[s] ? "rad" : "m";
}

}  // namespace

NonlinearModesResult run_nonlinear_modes(const model::Model& model, const NonlinearModesSettings& s,
                                         const Context& context) {
  NonlinearModesResult r;
  fe::LinearSystem own;
  const fe::LinearSystem& system = nonlinear_structure(model, context, own);
  const std::vector<BuiltNonlinearElement> elements =
      build_nonlinear_elements(model, system, context);
  const NonlinearCoordinates c = nonlinear_coordinates(system, s.speed, s.n_modes, context);
  const SensorRows sensors = nonlinear_sensor_rows(model, system, s.sensors, context);
  r.sensors = sensors.names;
  r.sensor_rotational = sensors.rotational;
  for (const auto& e : elements) r.elements.push_back(e.name);
  r.modal = c.modal;
  r.coordinates = static_cast<int>(c.M.rows());
  r.harmonics = s.harmonics;
  r.time_samples = s.time_samples > 0 ? s.time_samples : hbm::default_time_samples(s.harmonics);
  const hbm::HarmonicBasis basis(s.harmonics, r.time_samples);
  hbm::NonlinearModeOptions o;
  o.mode = s.mode - 1;
  o.amplitude_start = s.amplitude_start;
  o.amplitude_end = s.amplitude_stop;
  o.max_step = s.max_step;
  o.max_points = s.max_points;
  o.tolerance = s.tolerance;
  hbm::NonlinearModeResult modes;
  try {
    modes = hbm::nonlinear_mode(placed_element_system(c, elements, {}), basis, o);
  } catch (const InputError& e) {
    // The options were checked by the schema: what is left is the mode index or the mass.
    throw context.error(e.key_path() == "mode" ? "mode" : "n_modes", e.expected(), e.found(),
                        e.hint());
  }
  r.linear_frequency = modes.linear.omega;
  r.linear_damping_ratio = modes.linear.damping_ratio;
  const Eigen::MatrixXd sensors_q = sensors.rows * c.basis;
  const int sz = basis.size(), n = r.coordinates;
  r.element_energy.resize(static_cast<Eigen::Index>(modes.points.size()),
                          static_cast<Eigen::Index>(elements.size()));
  for (std::size_t i = 0; i < modes.points.size(); ++i) {
    const auto& p = modes.points[i];
    r.amplitude.push_back(p.amplitude);
    r.frequency.push_back(p.omega);
    r.damping_ratio.push_back(p.damping_ratio);
    r.energy.push_back(p.energy_per_cycle);
    const Eigen::Map<const Eigen::MatrixXd> Xs(p.X.data(), sz, n);
    r.sensor_coefficients.push_back(sensors_q * Xs.transpose());
    if (p.element_energy.size() == r.element_energy.cols())
      r.element_energy.row(static_cast<Eigen::Index>(i)) = p.element_energy.transpose();
  }
  if (modes.status != Status::Ok) {
    if (modes.points.empty())
      throw NumericalError(context.name(), "the nonlinear mode could not start: " + modes.message);
    r.status = Status::NotConverged;
    r.message = "the nonlinear mode ended before amplitude_stop: " + modes.message +
                ". The points up to there are converged.";
  }
  return r;
}

AnalysisOutput nonlinear_modes_output(const model::Model& /*model*/,
                                      const NonlinearModesSettings& s,
                                      const NonlinearModesResult& r, const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "nonlinear_modes";
  out.status = r.status;
  out.message = r.message;
  Table t;
  t.name = "backbone";
  t.title =
      fmt::format("Nonlinear mode {}: frequency, damping and energy against amplitude", s.mode);
  t.add("modal_amplitude", "sqrt(kg) m", r.amplitude);
  std::vector<double> hz(r.frequency.size());
  for (std::size_t i = 0; i < hz.size(); ++i) hz[i] = r.frequency[i] * kHz;
  t.add("frequency_hz", "Hz", hz);
  t.add("damping_ratio", "", r.damping_ratio);
  t.add("energy_per_cycle_j", "J", r.energy);
  std::vector<std::vector<double>> h1(r.sensors.size());
  for (std::size_t k = 0; k < r.sensors.size(); ++k) {
    std::vector<double> rms;
    for (const auto& c : r.sensor_coefficients) {
      const Eigen::VectorXd row = c.row(static_cast<Eigen::Index>(k)).transpose();
      h1[k].push_back(harmonic_amplitude(row, 1));
      rms.push_back(series_rms(row));
    }
    t.add(fmt::format("{}_h1_{}", r.sensors[k], unit_of(r, k)), unit_of(r, k), h1[k]);
    t.add(fmt::format("{}_rms_{}", r.sensors[k], unit_of(r, k)), unit_of(r, k), rms);
  }
  for (std::size_t e = 0; e < r.elements.size(); ++e) {
    const Eigen::VectorXd col = r.element_energy.col(static_cast<Eigen::Index>(e));
    t.add(r.elements[e] + "_energy_j", "J", std::vector<double>(col.begin(), col.end()));
  }
  out.tables.push_back(t);
  // Plots against the first sensor's amplitude (the modal amplitude without sensors).
  const bool by_sensor = !r.sensors.empty();
  const std::vector<double>& x = by_sensor ? h1[0] : r.amplitude;
  const std::string x_label =
      by_sensor ? fmt::format("{} first-harmonic amplitude [{}]", r.sensors[0], unit_of(r, 0))
                : "modal amplitude [sqrt(kg) m]";
  Plot f;
  f.name = "backbone";
  f.title = "Backbone: frequency against amplitude";
  f.x_label = x_label;
  f.y_label = "frequency [Hz]";
  f.x_log = true;
  Trace tf;
  tf.name = "frequency";
  tf.x = x;
  tf.y = hz;
  f.traces.push_back(tf);
  Plot d;
  d.name = "damping";
  d.title = "Damping ratio against amplitude";
  d.x_label = x_label;
  d.y_label = "damping ratio [-]";
  d.x_log = true;
  Trace td;
  td.name = "damping ratio";
  td.x = x;
  td.y = r.damping_ratio;
  d.traces.push_back(td);
  out.plots = {f, d};
  out.notes.push_back(fmt::format(
      "Extended periodic motion concept (Krack 2015), H = {} harmonics, {} time samples, {} {}. "
      "Linear mode {} at rest (elements linearised): {:.6g} Hz, damping ratio {:.4g}.",
      r.harmonics, r.time_samples, r.coordinates, r.modal ? "modal coordinates" : "DOFs", s.mode,
      r.linear_frequency * kHz, r.linear_damping_ratio));
  out.notes.push_back(
      "The damping ratio is xi / (2 omega) of the negative damping that makes the free motion "
      "periodic: exact for a linear mode of proportional damping, an energy-equivalent value "
      "otherwise (it reads the damping of a response near this mode's resonance).");
  return out;
}

}  // namespace geardyn::analyses
