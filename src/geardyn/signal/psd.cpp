#include "geardyn/signal/psd.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geardyn/signal/fft.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::signal {
namespace {

void check_inputs(const Eigen::Ref<const Eigen::VectorXd>& x, double fs, const WelchOptions& o) {
  if (!(fs > 0.0) || !std::isfinite(fs))
    throw std::invalid_argument("welch_psd: sample rate must be positive, got " +
                                std::to_string(fs));
  if (!x.allFinite()) throw std::invalid_argument("welch_psd: the signal has non-finite samples");
  if (!(o.overlap >= 0.0 && o.overlap < 1.0))
    throw std::invalid_argument("welch_psd: overlap must be in [0, 1), got " +
                                std::to_string(o.overlap));
  const int min_length = o.window == Window::Rectangular ? 1 : (o.window == Window::Hann ? 2 : 5);
  if (o.segment_length < min_length)
    throw std::invalid_argument("welch_psd: a " + std::string(to_string(o.window)) +
                                " window needs segments of at least " + std::to_string(min_length) +
                                " samples, got " + std::to_string(o.segment_length));
  if (x.size() < o.segment_length)
    throw std::invalid_argument("welch_psd: the record has " + std::to_string(x.size()) +
                                " samples, fewer than one segment of " +
                                std::to_string(o.segment_length));
}

}  // namespace

PowerSpectralDensity welch_psd(const Eigen::Ref<const Eigen::VectorXd>& x, double sample_rate_hz,
                               const WelchOptions& options) {
  check_inputs(x, sample_rate_hz, options);
  const int L = options.segment_length;
  const int n = static_cast<int>(x.size());
  const int shared = static_cast<int>(std::lround(options.overlap * L));
  const int step = L - shared < 1 ? 1 : L - shared;
  const int segments = (n - L) / step + 1;

  const Eigen::VectorXd w = window_coefficients(options.window, L);
  const double s1 = w.sum();
  const double s2 = w.squaredNorm();

  PowerSpectralDensity p;
  p.frequency_hz = frequency_axis(L, sample_rate_hz);
  p.sample_rate_hz = sample_rate_hz;
  p.resolution_hz = sample_rate_hz / L;
  p.enbw_hz = sample_rate_hz * s2 / (s1 * s1);
  p.segment_length = L;
  p.segments = segments;
  p.step = step;
  p.window = options.window;
  p.density = Eigen::VectorXd::Zero(L / 2 + 1);

  for (int s = 0; s < segments; ++s) {
    const Eigen::VectorXcd X =
        real_fft(x.segment(static_cast<Eigen::Index>(s) * step, L).cwiseProduct(w));
    p.density += X.cwiseAbs2();
  }
  const double scale = 1.0 / (sample_rate_hz * s2 * segments);
  for (int k = 0; k < p.density.size(); ++k) {
    const bool single = (k == 0) || (L % 2 == 0 && k == L / 2);  // DC and Nyquist: no mirror
    p.density[k] *= (single ? 1.0 : 2.0) * scale;
  }
  return p;
}

double total_power(const PowerSpectralDensity& psd) {
  return psd.density.sum() * psd.resolution_hz;
}

}  // namespace geardyn::signal
