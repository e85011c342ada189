#pragma once
// Peaks of a sampled amplitude curve |H(f)|: local maxima with a prominence, the peak refined by
// parabolic interpolation, and the half-power (-3 dB) bandwidth with the quality factor
//   Q = f_r / (f2 - f1),   zeta ~ 1 / (2 Q)                               (docs/theory.md §5, §14)
// where f1 < f_r < f2 are the frequencies at which the amplitude has fallen to A_peak / sqrt(2),
// found by linear interpolation of the amplitude between the two samples that bracket them.
// The abscissa may be in any unit (Hz, rad/s, rpm); Q is dimensionless.
// Reference: Ewins, Modal Testing: Theory, Practice and Application, 2nd ed., 2000, sec. 4.3
// (half-power point method).
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace geardyn::signal {

/// Vertex of the parabola through three points with x0 < x1 < x2 (any spacing).
/// `valid` is false when the points are collinear or the parabola opens upwards (no maximum).
struct ParabolaVertex {
  double x = std::numeric_limits<double>::quiet_NaN();
  double y = std::numeric_limits<double>::quiet_NaN();
  bool valid = false;
};
ParabolaVertex parabolic_vertex(double x0, double y0, double x1, double y1, double x2, double y2);

/// A local maximum of a sampled curve.
struct PeakIndex {
  std::size_t index = 0;    ///< sample of the maximum (middle sample of a flat top)
  double prominence = 0.0;  ///< height above the higher of the two bases, in the units of y
};

/// Local maxima of `y` (interior samples only) whose prominence is at least `min_prominence`,
/// in increasing index order. Prominence as in topography (and scipy.signal.peak_prominences):
/// from the peak walk left and right until a strictly higher sample or the end; the base on
/// each side is the lowest sample passed; prominence = y[peak] - max(left base, right base).
/// Pass dB values to measure prominence in dB. Throws std::invalid_argument for NaN samples.
std::vector<PeakIndex> find_peaks(std::span<const double> y, double min_prominence);

/// Half-power analysis of one peak.
struct HalfPower {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t peak_index = 0;  ///< the sampled maximum
  double frequency = kNaN;     ///< peak frequency refined by parabolic interpolation
  double amplitude = kNaN;     ///< peak amplitude refined by parabolic interpolation
  double f1 = kNaN;            ///< lower -3 dB crossing (NaN: not found)
  double f2 = kNaN;            ///< upper -3 dB crossing (NaN: not found)
  /// The crossings lie in [f[lower_bracket], f[lower_bracket + 1]] and
  /// [f[upper_bracket], f[upper_bracket + 1]] (meaningful only when found).
  std::size_t lower_bracket = 0, upper_bracket = 0;
  double bandwidth = kNaN;  ///< f2 - f1
  double q_factor = kNaN;   ///< frequency / bandwidth
  int points_in_band = 0;   ///< samples with f1 <= f <= f2
  bool has_lower() const { return !std::isnan(f1); }
  bool has_upper() const { return !std::isnan(f2); }
  bool has_bandwidth() const { return has_lower() && has_upper(); }
  /// 1 / (2 Q): the viscous damping ratio of a single, lightly damped mode.
  double damping_ratio() const { return 0.5 / q_factor; }
};

/// Half-power analysis of the peak at sample `peak_index` of the amplitude curve `amplitude(f)`
/// (f strictly increasing, amplitude >= 0). The search for a crossing on one side stops without
/// result at the end of the data or at a sample higher than the sampled peak (another, larger
/// peak before the curve fell by 3 dB). A peak at the first or last sample is not refined.
/// Throws std::invalid_argument for inconsistent sizes or an index out of range.
HalfPower half_power(std::span<const double> f, std::span<const double> amplitude,
                     std::size_t peak_index);

}  // namespace geardyn::signal
