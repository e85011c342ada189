#pragma once
// Internal to the forced responses to gear-mesh excitation (cyclic_forced_response,
// gear_forced_response): reading a measured response over speed and comparing a computed curve
// with it. Not part of the analyses' interface.
#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The measured curve of a cyclic forced response: a displacement amplitude over speed.
gear::MeasuredResponse read_measured(const model::Model& model, const std::string& name,
                                     const std::string& file);

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
                          const std::vector<double>& used);

/// Compares a computed curve over speed with the measured `m` (table and note into `out`).
MeasuredComparison compare_with_measured(AnalysisOutput& out, const gear::MeasuredResponse& m,
                                         const std::vector<double>& rpm,
                                         const std::vector<double>& computed,
                                         const std::string& curve_name, double min_prominence_db);

}  // namespace geardyn::analyses
