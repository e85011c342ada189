#pragma once
// Internal to the forced responses to gear-mesh excitation (cyclic_forced_response,
// gear_forced_response): reading a measured response over speed and comparing a computed curve
// with it. Not part of the analyses' interface.
#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The measured curve of a cyclic forced response: a displacement amplitude over speed.
/// InputError at measured_file when it is not a displacement over speed.
gear::MeasuredResponse read_measured(const model::Model& model, const Context& context,
                                     const std::string& file);

/// Index of the sensor a measured curve is compared with: `wanted` by name, or the first one.
/// InputError at measured_sensor when no sensor has that name.
template <class Sensor>
std::size_t measured_sensor_index(const std::vector<Sensor>& sensors, const std::string& wanted,
                                  const Context& context) {
  if (wanted.empty()) return 0;
  auto it =
      std::find_if(sensors.begin(), sensors.end(), [&](const auto& x) { return x.name == wanted; });
  if (it == sensors.end()) {
    std::string names;
    for (const auto& x : sensors) names += (names.empty() ? "" : ", ") + x.name;
    throw context.error("measured_sensor", fmt::format("a sensor of this analysis ({})", names),
                        fmt::format("\"{}\"", wanted));
  }
  return static_cast<std::size_t>(it - sensors.begin());
}

/// The comparison of a computed response over speed with a measured one, shared by the forced
/// responses (A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped
/// with Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 5.2): the overlay plot
/// (measured markers, computed line; the caller may add traces before pushing it), the peak table
/// and a note on the largest measured peak.
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
                          const std::vector<double>& used);

/// The peaks of the measured `m` matched with those of the computed curve (empty: no prominent
/// measured peak), and the index of the largest measured one.
std::vector<gear::PeakComparison> measured_peaks(const gear::MeasuredResponse& m,
                                                 const std::vector<double>& rpm,
                                                 const std::vector<double>& computed,
                                                 double min_prominence_db);
std::size_t largest_measured_peak(const std::vector<gear::PeakComparison>& peaks);

/// Compares a computed curve over speed with the measured `m` (table and note into `out`).
MeasuredComparison compare_with_measured(AnalysisOutput& out, const gear::MeasuredResponse& m,
                                         const std::vector<double>& rpm,
                                         const std::vector<double>& computed,
                                         const std::string& curve_name, double min_prominence_db);

/// Scalars of a sampled curve a(x) (x increasing), for the types' `scalar`: the index of its
/// largest sample (std::runtime_error when empty), and its value at `at` by linear
/// interpolation between the samples around it (std::runtime_error outside [x0, xn]; the message
/// gives `at` times `per_unit` in `unit`).
std::size_t largest_sample(const std::vector<double>& a);
double value_at(const std::vector<double>& x, const std::vector<double>& a, double at,
                double per_unit, const std::string& unit);

/// The scalars every forced response over speed offers, of one sensor's curve `amplitude` over
/// `speeds` [rad/s] in `curve_unit` ("m" or "rad"): peak_amplitude (its largest sample),
/// peak_location (the speed of that sample, rpm) and amplitude_at (at `q.at`, linear
/// interpolation). `unit` is set to the value's unit.
double speed_curve_scalar(const std::vector<double>& speeds, const std::vector<double>& amplitude,
                          const ScalarRequest& q, const std::string& curve_unit, std::string& unit);

/// Index of the sensor called `name` (empty: the first) in `sensors`; std::runtime_error (a
/// scalar request the result cannot answer) when there is none.
template <class Sensor>
std::size_t requested_sensor(const std::vector<Sensor>& sensors, const std::string& name) {
  if (sensors.empty()) throw std::runtime_error("the analysis has no sensor");
  if (name.empty()) return 0;
  for (std::size_t i = 0; i < sensors.size(); ++i)
    if (sensors[i].name == name) return i;
  throw std::runtime_error(fmt::format("the analysis has no sensor '{}'", name));
}

}  // namespace geardyn::analyses
