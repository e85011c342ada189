#include "geardyn/signal/half_power.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geardyn::signal {

ParabolaVertex parabolic_vertex(double x0, double y0, double x1, double y1, double x2, double y2) {
  ParabolaVertex v;
  // Newton form: p(x) = y0 + d01 (x - x0) + a (x - x0)(x - x1), with divided differences.
  const double h0 = x1 - x0, h1 = x2 - x1;
  if (!(h0 > 0.0) || !(h1 > 0.0)) return v;
  const double d01 = (y1 - y0) / h0;
  const double d12 = (y2 - y1) / h1;
  const double a = (d12 - d01) / (x2 - x0);
  if (!(a < 0.0)) return v;  // collinear or opening upwards: no maximum
  // p'(x) = d01 + a (2x - x0 - x1) = 0
  v.x = 0.5 * (x0 + x1) - d01 / (2.0 * a);
  v.y = y0 + d01 * (v.x - x0) + a * (v.x - x0) * (v.x - x1);
  v.valid = std::isfinite(v.x) && std::isfinite(v.y);
  return v;
}

std::vector<PeakIndex> find_peaks(std::span<const double> y, double min_prominence) {
  const std::size_t n = y.size();
  for (std::size_t i = 0; i < n; ++i)
    if (std::isnan(y[i]))
      throw std::invalid_argument("find_peaks: sample " + std::to_string(i) + " is NaN");
  std::vector<PeakIndex> peaks;
  std::size_t i = 1;
  while (i + 1 < n) {
    if (!(y[i] > y[i - 1])) {
      ++i;
      continue;
    }
    // y rises into i; skip a flat top and require a fall after it.
    std::size_t j = i;
    while (j + 1 < n && y[j + 1] == y[i]) ++j;
    if (j + 1 < n && y[j + 1] < y[i]) {
      const std::size_t peak = (i + j) / 2;
      const double height = y[peak];
      double left_base = height;
      for (std::size_t k = i; k-- > 0;) {
        if (y[k] > height) break;
        left_base = std::min(left_base, y[k]);
      }
      double right_base = height;
      for (std::size_t k = j + 1; k < n; ++k) {
        if (y[k] > height) break;
        right_base = std::min(right_base, y[k]);
      }
      const double prominence = height - std::max(left_base, right_base);
      if (prominence >= min_prominence) peaks.push_back({peak, prominence});
    }
    i = j + 1;
  }
  return peaks;
}

HalfPower half_power(std::span<const double> f, std::span<const double> amplitude,
                     std::size_t peak_index) {
  const std::size_t n = f.size();
  if (amplitude.size() != n)
    throw std::invalid_argument("half_power: frequency and amplitude sizes differ");
  if (peak_index >= n) throw std::invalid_argument("half_power: peak index out of range");
  HalfPower hp;
  hp.peak_index = peak_index;
  hp.frequency = f[peak_index];
  hp.amplitude = amplitude[peak_index];
  if (peak_index > 0 && peak_index + 1 < n) {
    const auto v =
        parabolic_vertex(f[peak_index - 1], amplitude[peak_index - 1], f[peak_index],
                         amplitude[peak_index], f[peak_index + 1], amplitude[peak_index + 1]);
    // A vertex below the sampled maximum cannot be the peak (the samples are exact values).
    if (v.valid && v.y >= amplitude[peak_index] && v.x > f[peak_index - 1] &&
        v.x < f[peak_index + 1]) {
      hp.frequency = v.x;
      hp.amplitude = v.y;
    }
  }
  const double sampled_peak = amplitude[peak_index];
  const double level = hp.amplitude / std::sqrt(2.0);

  // Lower crossing: walk left while the curve stays above the level.
  for (std::size_t k = peak_index; k-- > 0;) {
    if (amplitude[k] > sampled_peak) break;
    if (amplitude[k] < level) {
      const double s = (level - amplitude[k]) / (amplitude[k + 1] - amplitude[k]);
      hp.f1 = f[k] + s * (f[k + 1] - f[k]);
      hp.lower_bracket = k;
      break;
    }
  }
  for (std::size_t k = peak_index + 1; k < n; ++k) {
    if (amplitude[k] > sampled_peak) break;
    if (amplitude[k] < level) {
      const double s = (amplitude[k - 1] - level) / (amplitude[k - 1] - amplitude[k]);
      hp.f2 = f[k - 1] + s * (f[k] - f[k - 1]);
      hp.upper_bracket = k - 1;
      break;
    }
  }
  if (hp.has_bandwidth()) {
    hp.bandwidth = hp.f2 - hp.f1;
    hp.q_factor = hp.frequency / hp.bandwidth;
    for (std::size_t k = hp.lower_bracket; k <= hp.upper_bracket + 1; ++k)
      if (f[k] >= hp.f1 && f[k] <= hp.f2) ++hp.points_in_band;
  }
  return hp;
}

}  // namespace geardyn::signal
