#include "geardyn/response/speed_peaks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "geardyn/core/error.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::response {

void check_speeds(const Eigen::VectorXd& speeds, const std::string& key) {
  if (speeds.size() == 0) throw InputError({}, key, "at least one speed", "an empty list");
  for (Eigen::Index i = 0; i < speeds.size(); ++i) {
    if (!std::isfinite(speeds[i]) || !(speeds[i] > 0.0))
      throw InputError({}, fmt::format("{}[{}]", key, i), "a finite positive speed [rad/s]",
                       fmt::format("{}", speeds[i]),
                       "the response at zero speed is static (omega = k W = 0); start above 0");
    if (i > 0 && !(speeds[i] > speeds[i - 1]))
      throw InputError({}, fmt::format("{}[{}]", key, i), "strictly increasing speeds",
                       fmt::format("{} after {}", speeds[i], speeds[i - 1]),
                       "sort the speeds and remove repeats");
  }
}

std::vector<std::string> PeakOptions::validate() const {
  std::vector<std::string> problems;
  if (!(min_prominence_db >= 0.0) || !std::isfinite(min_prominence_db))
    problems.push_back(
        fmt::format("min_prominence_db must be finite and >= 0, is {}", min_prominence_db));
  if (min_points_in_band < 1)
    problems.push_back(fmt::format("min_points_in_band must be >= 1, is {}", min_points_in_band));
  return problems;
}

std::vector<SpeedPeak> find_speed_peaks(const Eigen::VectorXd& speeds,
                                        const Eigen::VectorXd& amplitude, int sensor, int curve,
                                        const PeakOptions& options) {
  if (speeds.size() != amplitude.size())
    throw InputError({}, "peaks", "one amplitude per speed",
                     fmt::format("{} speeds, {} amplitudes", speeds.size(), amplitude.size()));
  if (const auto problems = options.validate(); !problems.empty())
    throw InputError({}, "peaks", "valid peak options", problems.front());
  const Eigen::Index n = speeds.size();
  Eigen::VectorXd db(n);
  for (Eigen::Index i = 0; i < n; ++i) db[i] = 20.0 * std::log10(std::max(amplitude[i], 1e-300));
  const std::span<const double> x(speeds.data(), static_cast<std::size_t>(n));
  const std::span<const double> y(amplitude.data(), static_cast<std::size_t>(n));
  std::vector<SpeedPeak> peaks;
  for (const signal::PeakIndex& p :
       signal::find_peaks(std::span<const double>(db.data(), static_cast<std::size_t>(n)),
                          options.min_prominence_db)) {
    const signal::HalfPower hp = signal::half_power(x, y, p.index);
    SpeedPeak peak;
    peak.sensor = sensor;
    peak.curve = curve;
    peak.speed = hp.frequency;
    peak.amplitude = hp.amplitude;
    peak.speed1 = hp.f1;
    peak.speed2 = hp.f2;
    peak.q_factor = hp.has_bandwidth() ? hp.q_factor : kNaN;
    peak.points_in_band = hp.points_in_band;
    peak.resolved = hp.has_bandwidth() && hp.points_in_band >= options.min_points_in_band;
    peaks.push_back(peak);
  }
  return peaks;
}

void append_speed_peaks(std::vector<SpeedPeak>& peaks, const Eigen::VectorXd& speeds,
                        const Eigen::MatrixXd& amplitude, int curve, const PeakOptions& options) {
  for (Eigen::Index s = 0; s < amplitude.cols(); ++s) {
    const auto found =
        find_speed_peaks(speeds, amplitude.col(s), static_cast<int>(s), curve, options);
    peaks.insert(peaks.end(), found.begin(), found.end());
  }
}

}  // namespace geardyn::response
