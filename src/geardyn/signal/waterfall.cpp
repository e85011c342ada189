#include "geardyn/signal/waterfall.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "geardyn/core/units.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::signal {
namespace {

void check_options(const WaterfallOptions& o) {
  if (!(o.overlap >= 0.0 && o.overlap < 1.0))
    throw std::invalid_argument("waterfall: overlap must be in [0, 1), got " +
                                std::to_string(o.overlap));
  const int min_length = o.window == Window::Rectangular ? 1 : (o.window == Window::Hann ? 2 : 5);
  if (o.block_length < min_length)
    throw std::invalid_argument("waterfall: a " + std::string(to_string(o.window)) +
                                " window needs blocks of at least " + std::to_string(min_length) +
                                " samples, got " + std::to_string(o.block_length));
}

// The blocks of x and their spectra; `block_speed(start, length)` gives each block's speed.
Waterfall compute(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                  const Eigen::Ref<const Eigen::VectorXd>& x, const WaterfallOptions& o,
                  const std::function<double(Eigen::Index, Eigen::Index)>& block_speed) {
  check_options(o);
  if (time_s.size() != x.size())
    throw std::invalid_argument("waterfall: " + std::to_string(time_s.size()) + " times but " +
                                std::to_string(x.size()) + " values");
  const double fs = uniform_sample_rate(time_s);
  if (!x.allFinite()) throw std::invalid_argument("waterfall: the signal has non-finite samples");
  const Eigen::Index n = x.size();
  const int L = o.block_length;
  if (n < L)
    throw std::invalid_argument("waterfall: the record has " + std::to_string(n) +
                                " samples, fewer than one block of " + std::to_string(L));
  const int shared = static_cast<int>(std::lround(o.overlap * L));
  const int step = L - shared < 1 ? 1 : L - shared;
  const auto blocks = static_cast<Eigen::Index>((n - L) / step + 1);

  Waterfall w;
  w.frequency_hz = frequency_axis(L, fs);
  w.sample_rate_hz = fs;
  w.resolution_hz = fs / L;
  w.block_length = L;
  w.step = step;
  w.window = o.window;
  w.amplitude.resize(blocks, w.frequency_hz.size());
  w.speed_rpm.resize(blocks);
  w.time_s.resize(blocks);
  for (Eigen::Index b = 0; b < blocks; ++b) {
    const Eigen::Index start = b * step;
    w.amplitude.row(b) =
        amplitude_spectrum(x.segment(start, L), fs, o.window).amplitude.transpose();
    w.speed_rpm[b] = block_speed(start, L);
    w.time_s[b] = 0.5 * (time_s[start] + time_s[start + L - 1]);
  }
  return w;
}

}  // namespace

double uniform_sample_rate(const Eigen::Ref<const Eigen::VectorXd>& time_s) {
  const Eigen::Index n = time_s.size();
  if (n < 2) throw std::invalid_argument("time axis: fewer than 2 samples");
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!std::isfinite(time_s[j]))
      throw std::invalid_argument("time is not finite at sample " + std::to_string(j));
    if (j > 0 && !(time_s[j] > time_s[j - 1]))
      throw std::invalid_argument("time is not strictly increasing at sample " + std::to_string(j) +
                                  " (" + std::to_string(time_s[j]) + " after " +
                                  std::to_string(time_s[j - 1]) + ")");
  }
  const double mean_step = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);
  for (Eigen::Index j = 1; j < n; ++j)
    if (std::abs(time_s[j] - time_s[j - 1] - mean_step) > 1e-6 * mean_step)
      throw std::invalid_argument("time is not uniformly sampled at sample " + std::to_string(j) +
                                  " (step " + std::to_string(time_s[j] - time_s[j - 1]) +
                                  " s, mean step " + std::to_string(mean_step) + " s)");
  return 1.0 / mean_step;
}

Waterfall waterfall_by_angle(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                             const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& angle_rad,
                             const WaterfallOptions& options) {
  if (angle_rad.size() != time_s.size())
    throw std::invalid_argument("waterfall: " + std::to_string(time_s.size()) + " times but " +
                                std::to_string(angle_rad.size()) + " angles");
  if (!angle_rad.allFinite())
    throw std::invalid_argument("waterfall: the shaft angle has non-finite samples");
  return compute(time_s, x, options, [&](Eigen::Index start, Eigen::Index length) {
    const Eigen::Index end = start + length - 1;
    return 60.0 * (angle_rad[end] - angle_rad[start]) /
           (units::kTwoPi * (time_s[end] - time_s[start]));
  });
}

Waterfall waterfall_by_speed(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                             const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& speed_rpm,
                             const WaterfallOptions& options) {
  if (speed_rpm.size() != time_s.size())
    throw std::invalid_argument("waterfall: " + std::to_string(time_s.size()) + " times but " +
                                std::to_string(speed_rpm.size()) + " speeds");
  if (!speed_rpm.allFinite())
    throw std::invalid_argument("waterfall: the speed has non-finite samples");
  return compute(time_s, x, options, [&](Eigen::Index start, Eigen::Index length) {
    return speed_rpm.segment(start, length).mean();
  });
}

Eigen::VectorXd order_line_hz(double order, const Eigen::Ref<const Eigen::VectorXd>& speed_rpm) {
  return order * speed_rpm / 60.0;
}

}  // namespace geardyn::signal
