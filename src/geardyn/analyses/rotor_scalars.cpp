// Scalar outputs of the rotor analyses from their typed results.
#include "geardyn/analyses/rotor_scalars.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geardyn::analyses {

double response_scalar(const ResponseCurve& curve, const ScalarRequest& request,
                       std::string& unit) {
  const bool peak = request.quantity == "peak_amplitude" || request.quantity == "peak_location";
  if (peak) {
    const std::vector<double>& amp = curve.amplitude;
    if (amp.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::size_t best = 0;
    for (std::size_t i = 1; i < amp.size(); ++i)
      if (amp[i] > amp[best]) best = i;
    const bool amplitude = request.quantity == "peak_amplitude";
    unit = amplitude ? curve.amplitude_unit : curve.x_unit;
    return amplitude ? amp[best] : curve.x[best];
  }
  if (request.quantity != "amplitude_at") unknown_scalar("response", request.quantity);
  // Linear interpolation per order group, the largest over groups.
  unit = curve.amplitude_unit;
  const double at = request.at * curve.per_rad_s;
  double result = std::numeric_limits<double>::quiet_NaN();
  for (const auto& rows : curve.groups) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const double xk = curve.x[rows[k]];
      double value = std::numeric_limits<double>::quiet_NaN();
      if (std::abs(xk - at) <= 1e-9 * std::max(1.0, std::abs(at))) {
        value = curve.amplitude[rows[k]];
      } else if (k + 1 < rows.size()) {
        const double x1 = curve.x[rows[k + 1]];
        if ((xk - at) * (x1 - at) < 0.0) {
          const double s = (at - xk) / (x1 - xk);
          value = (1.0 - s) * curve.amplitude[rows[k]] + s * curve.amplitude[rows[k + 1]];
        }
      }
      if (!std::isnan(value) && (std::isnan(result) || value > result)) result = value;
    }
  }
  if (std::isnan(result))
    throw std::runtime_error(fmt::format("{} {} is outside the analysis range", at, curve.x_unit));
  return result;
}

void unknown_scalar(const std::string& type, const std::string& quantity) {
  throw std::logic_error(fmt::format("the {} analysis offers no scalar '{}'", type, quantity));
}

}  // namespace geardyn::analyses
