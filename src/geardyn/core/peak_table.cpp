#include "geardyn/core/peak_table.hpp"

#include <cmath>

namespace geardyn {

PeakAxis frequency_axis() { return {"frequency", "hz", "Hz"}; }
PeakAxis speed_axis() { return {"speed", "rpm", "rpm"}; }

Table peak_table(std::string name, std::string title, const PeakAxis& axis,
                 const std::vector<PeakRow>& peaks) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> index, x, amp, x1, x2, q, zeta, band, resolved;
  std::vector<std::string> sensor, curve, unit;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const PeakRow& p = peaks[i];
    index.push_back(static_cast<double>(i + 1));
    sensor.push_back(p.sensor);
    curve.push_back(p.curve);
    x.push_back(p.location);
    amp.push_back(p.amplitude);
    unit.push_back(p.amplitude_unit);
    x1.push_back(p.half_power_low);
    x2.push_back(p.half_power_high);
    const bool q_known = p.resolved && std::isfinite(p.q_factor) && p.q_factor > 0.0;
    q.push_back(q_known ? p.q_factor : kNaN);
    zeta.push_back(q_known ? 0.5 / p.q_factor : kNaN);
    band.push_back(static_cast<double>(p.points_in_band));
    resolved.push_back(p.resolved ? 1.0 : 0.0);
  }
  const std::string x_name = axis.stem + "_" + axis.suffix;
  Table t;
  t.name = std::move(name);
  t.title = std::move(title);
  t.add("peak", "", std::move(index));
  t.add_text("sensor", std::move(sensor));
  t.add_text("curve", std::move(curve));
  t.add(x_name, axis.unit, std::move(x));
  t.add("amplitude", "", std::move(amp));
  t.add_text("amplitude_unit", std::move(unit));
  t.add("half_power_low_" + x_name, axis.unit, std::move(x1));
  t.add("half_power_high_" + x_name, axis.unit, std::move(x2));
  t.add("q_factor", "", std::move(q));
  t.add("damping_ratio", "", std::move(zeta));
  t.add("points_in_band", "", std::move(band));
  t.add("resolved", "", std::move(resolved));
  return t;
}

}  // namespace geardyn
