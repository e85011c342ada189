// Test oracle: scalar outputs read back from result tables (see table_scalars.hpp).
#include "analyses/table_scalars.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace geardyn::analyses {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Quantity { NaturalFrequency, CriticalSpeed, PeakAmplitude, PeakLocation, AmplitudeAt };

Quantity quantity_of(const std::string& name) {
  if (name == "natural_frequency") return Quantity::NaturalFrequency;
  if (name == "critical_speed") return Quantity::CriticalSpeed;
  if (name == "peak_amplitude") return Quantity::PeakAmplitude;
  if (name == "peak_location") return Quantity::PeakLocation;
  if (name == "amplitude_at") return Quantity::AmplitudeAt;
  throw std::logic_error("no table reader for the scalar '" + name + "'");
}

const Table* find_table(const AnalysisOutput& output, std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (const auto& t : output.tables)
      if (t.name == name) return &t;
  return nullptr;
}

// The response column of a sensor: "<sensor>_amplitude..." (FRF, unbalance response).
const Column* amplitude_column(const Table& table, const std::string& sensor) {
  const std::string stem = sensor + "_amplitude";
  for (const auto& c : table.columns)
    if (!c.text && c.name.rfind(stem, 0) == 0) return &c;
  return nullptr;
}

// The abscissa of a response table and the factor from rad/s to its unit.
const Column* abscissa(const Table& table, double& per_rad_s) {
  if (table.has_column("speed_rpm")) {
    per_rad_s = 60.0 / (2.0 * std::numbers::pi);
    return &table.column("speed_rpm");
  }
  if (table.has_column("frequency_hz")) {
    per_rad_s = 1.0 / (2.0 * std::numbers::pi);
    return &table.column("frequency_hz");
  }
  return nullptr;
}

// Rows grouped by excitation order (unbalance tables carry an `order` column); a single group
// otherwise. Each group's abscissa is increasing.
std::vector<std::vector<std::size_t>> order_groups(const Table& table) {
  std::vector<std::vector<std::size_t>> groups;
  if (!table.has_column("order")) {
    groups.emplace_back();
    for (std::size_t i = 0; i < table.rows(); ++i) groups.back().push_back(i);
    return groups;
  }
  const auto& order = table.column("order").numbers;
  std::vector<double> seen;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    auto it = std::find(seen.begin(), seen.end(), order[i]);
    if (it == seen.end()) {
      seen.push_back(order[i]);
      groups.emplace_back();
      it = seen.end() - 1;
    }
    groups[static_cast<std::size_t>(it - seen.begin())].push_back(i);
  }
  return groups;
}

}  // namespace

double scalar_from_tables(const Outcome& outcome, const ScalarRequest& spec, std::string& unit) {
  const AnalysisOutput& output = outcome.output;
  using Q = Quantity;
  const Quantity quantity = quantity_of(spec.quantity);
  switch (quantity) {
    case Q::NaturalFrequency: {
      const Table* t = find_table(output, {"modes", "undamped_modes"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no modes table (use a modal analysis)");
      unit = "Hz";
      const auto& f = t->column("frequency_hz").numbers;
      const auto row = static_cast<std::size_t>(spec.mode - 1);
      if (row >= f.size())
        throw std::runtime_error(fmt::format("mode {} requested, {} found", spec.mode, f.size()));
      return f[row];
    }
    case Q::CriticalSpeed: {
      const Table* t = find_table(output, {"critical_speeds"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no critical_speeds table (use a campbell analysis)");
      unit = "rpm";
      std::vector<double> speeds = t->column("speed_rpm").numbers;
      std::sort(speeds.begin(), speeds.end());
      const auto row = static_cast<std::size_t>(spec.mode - 1);
      return row < speeds.size() ? speeds[row] : kNaN;  // none in range: NaN, not an error
    }
    case Q::PeakAmplitude:
    case Q::PeakLocation:
    case Q::AmplitudeAt: {
      const Table* t = find_table(output, {"frf", "response"});
      if (t == nullptr)
        throw std::runtime_error("analysis has no response table (use harmonic or unbalance)");
      const Column* amp = amplitude_column(*t, spec.sensor);
      if (amp == nullptr)
        throw std::runtime_error(fmt::format("no amplitude column for sensor '{}'", spec.sensor));
      double per_rad_s = 1.0;
      const Column* x = abscissa(*t, per_rad_s);
      if (x == nullptr) throw std::runtime_error("response table has no speed or frequency column");
      if (quantity == Q::PeakAmplitude || quantity == Q::PeakLocation) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < amp->numbers.size(); ++i)
          if (amp->numbers[i] > amp->numbers[best]) best = i;
        if (amp->numbers.empty()) return kNaN;
        unit = quantity == Q::PeakAmplitude ? amp->unit : x->unit;
        return quantity == Q::PeakAmplitude ? amp->numbers[best] : x->numbers[best];
      }
      // AmplitudeAt: linear interpolation per order group, the largest over groups.
      unit = amp->unit;
      const double at = spec.at * per_rad_s;
      double result = kNaN;
      for (const auto& rows : order_groups(*t)) {
        for (std::size_t k = 0; k < rows.size(); ++k) {
          const double xk = x->numbers[rows[k]];
          double value = kNaN;
          if (std::abs(xk - at) <= 1e-9 * std::max(1.0, std::abs(at))) {
            value = amp->numbers[rows[k]];
          } else if (k + 1 < rows.size()) {
            const double x1 = x->numbers[rows[k + 1]];
            if ((xk - at) * (x1 - at) < 0.0) {
              const double s = (at - xk) / (x1 - xk);
              value = (1.0 - s) * amp->numbers[rows[k]] + s * amp->numbers[rows[k + 1]];
            }
          }
          if (!std::isnan(value) && (std::isnan(result) || value > result)) result = value;
        }
      }
      if (std::isnan(result))
        throw std::runtime_error(fmt::format("{} {} is outside the analysis range", at, x->unit));
      return result;
    }
  }
  return kNaN;
}

}  // namespace geardyn::analyses
