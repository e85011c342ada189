#include "geardyn/signal/spectrum.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geardyn/signal/fft.hpp"

namespace geardyn::signal {

Eigen::VectorXd frequency_axis(int n, double sample_rate_hz) {
  if (n < 1) throw std::invalid_argument("frequency_axis: n must be at least 1");
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
    throw std::invalid_argument("frequency_axis: sample rate must be positive, got " +
                                std::to_string(sample_rate_hz));
  const int half = n / 2 + 1;
  Eigen::VectorXd f(half);
  for (int k = 0; k < half; ++k) f[k] = k * sample_rate_hz / static_cast<double>(n);
  return f;
}

AmplitudeSpectrum amplitude_spectrum(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     double sample_rate_hz, Window window) {
  const int n = static_cast<int>(x.size());
  if (n < 1) throw std::invalid_argument("amplitude_spectrum: empty signal");
  if (!x.allFinite())
    throw std::invalid_argument("amplitude_spectrum: the signal has non-finite samples");

  // Shorter signals make sum(w) degenerate (Hann of length 1 is 0; the flat top's coherent
  // gain equals a_0 only from n = 5 on).
  const int min_length = window == Window::Rectangular ? 1 : (window == Window::Hann ? 2 : 5);
  if (n < min_length)
    throw std::invalid_argument("amplitude_spectrum: a " + std::string(to_string(window)) +
                                " window needs at least " + std::to_string(min_length) +
                                " samples, got " + std::to_string(n));

  AmplitudeSpectrum s;
  s.frequency_hz = frequency_axis(n, sample_rate_hz);
  s.sample_rate_hz = sample_rate_hz;
  s.resolution_hz = sample_rate_hz / n;
  s.samples = n;
  s.window = window;

  const Eigen::VectorXd w = window_coefficients(window, n);
  const Eigen::VectorXcd X = real_fft(x.cwiseProduct(w));
  // Coherent-gain correction: dividing by sum(w) = n CG instead of n makes an on-bin sinusoid
  // read its amplitude whatever the window.
  const double scale = 1.0 / w.sum();
  const int half = static_cast<int>(X.size());
  s.amplitude.resize(half);
  s.phase.resize(half);
  for (int k = 0; k < half; ++k) {
    const bool single = (k == 0) || (n % 2 == 0 && k == n / 2);  // DC and Nyquist: no mirror
    s.amplitude[k] = (single ? 1.0 : 2.0) * std::abs(X[k]) * scale;
    s.phase[k] = std::arg(X[k]);
  }
  return s;
}

}  // namespace geardyn::signal
