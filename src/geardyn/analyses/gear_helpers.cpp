#include "geardyn/analyses/gear_helpers.hpp"

#include <fmt/format.h>

#include <utility>

#include "geardyn/core/units.hpp"

namespace geardyn::analyses {

double to_rpm(double omega) { return omega * 60.0 / units::kTwoPi; }

std::string rpm_text(double rpm) { return fmt::format("{:.6g} rpm", rpm); }

std::vector<double> scaled(const std::vector<double>& v, double factor) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * factor;
  return out;
}

Trace line(std::string name, std::vector<double> x, std::vector<double> y, Trace::Mode mode,
           std::string dash) {
  Trace t;
  t.name = std::move(name);
  t.x = std::move(x);
  t.y = std::move(y);
  t.mode = mode;
  t.dash = std::move(dash);
  return t;
}

}  // namespace geardyn::analyses
