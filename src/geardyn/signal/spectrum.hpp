#pragma once
// One-sided amplitude spectrum of a real, uniformly sampled signal (docs/theory.md §12.2, §14).
//
// With n samples x_j at sample rate fs, window w_j and coherent gain CG = sum(w)/n:
//   X_k = sum_j w_j x_j exp(-2 pi i j k / n),        f_k = k fs / n,  k = 0 .. n/2
//   A_0 = |X_0| / (n CG)            (the mean of the signal, not doubled; sign dropped)
//   A_k = 2 |X_k| / (n CG)          (0 < k < n/2)
//   A_{n/2} = |X_{n/2}| / (n CG)    (Nyquist bin of an even n, not doubled)
// A_k is the 0-peak amplitude: x_j = a cos(2 pi f_k t_j + phi) on bin k reads A_k = a exactly for
// every window (for the periodic windows of window.hpp). Between bins the reading drops by at
// most max_scalloping_loss(window). Peak-to-peak would be 2 A_k; this module never reports it.
// Parseval (rectangular window): mean(x^2) = A_0^2 + sum_{0<k<n/2} A_k^2 / 2 + A_{n/2}^2.
#include <Eigen/Dense>

#include "geardyn/signal/window.hpp"

namespace geardyn::signal {

struct AmplitudeSpectrum {
  Eigen::VectorXd frequency_hz;  ///< f_k = k fs / n [Hz], k = 0 .. n/2
  Eigen::VectorXd amplitude;     ///< 0-peak amplitude A_k, in the unit of the signal
  Eigen::VectorXd phase;         ///< arg X_k [rad] of the windowed signal (cosine phase
                                 ///< at t = 0 for a rectangular window, on-bin)
  double sample_rate_hz = 0.0;
  double resolution_hz = 0.0;  ///< fs / n
  int samples = 0;
  Window window = Window::Hann;
};

/// Frequency axis f_k = k fs / n, k = 0 .. n/2 [Hz]. Throws std::invalid_argument for n < 1 or
/// fs <= 0.
Eigen::VectorXd frequency_axis(int n, double sample_rate_hz);

/// One-sided amplitude spectrum of x (see the formulas above). Throws std::invalid_argument for
/// a non-positive sample rate, non-finite samples, or fewer samples than the window needs
/// (rectangular 1, Hann 2, flat top 5).
AmplitudeSpectrum amplitude_spectrum(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     double sample_rate_hz, Window window = Window::Hann);

}  // namespace geardyn::signal
