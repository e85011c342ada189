#pragma once
// Welch power spectral density of a real, uniformly sampled signal (docs/theory.md §14).
//
// The record is cut into K segments of L samples, each starting `step` = L - round(overlap L)
// samples after the previous one (K = floor((N - L)/step) + 1; samples after the last full
// segment are not used). Each segment is multiplied by the window w and transformed, and the
// one-sided densities are averaged:
//   P_k = c_k / (fs S2) * (1/K) sum_segments |X_k|^2,   S2 = sum_j w_j^2,   f_k = k fs / L
// with c_k = 1 for DC and (L even) Nyquist, 2 otherwise. Dividing by S2, the window's power
// (equivalently: by the equivalent noise bandwidth ENBW = fs S2 / S1^2 after the coherent-gain
// correction 1/S1^2), makes the PSD integrate to the mean square:
//   sum_k P_k fs/L = (1/K) sum_segments sum_j (w_j x_j)^2 / S2,
// which for a rectangular window and non-overlapping segments is exactly the mean square of the
// samples used, and for any window its expectation for stationary noise. The unit is
// (unit of the signal)^2 / Hz. A sinusoid of amplitude A contributes A^2/2 summed over its
// leakage bins.
// References: P. D. Welch, "The use of fast Fourier transform for the estimation of power
// spectra: a method based on time averaging over short, modified periodograms", IEEE Trans.
// Audio Electroacoust. 15 (1967) 70-73; G. Heinzel, A. Ruediger, R. Schilling, "Spectrum and
// spectral density estimation by the Discrete Fourier transform (DFT)", 2002 (sections 9-10).
#include <Eigen/Dense>

#include "geardyn/signal/window.hpp"

namespace geardyn::signal {

struct WelchOptions {
  int segment_length = 1024;  ///< L, samples per segment (also the DFT length)
  Window window = Window::Hann;
  double overlap = 0.5;  ///< fraction of L shared by consecutive segments, 0 <= overlap < 1
};

struct PowerSpectralDensity {
  Eigen::VectorXd frequency_hz;  ///< f_k = k fs / L [Hz], k = 0 .. L/2
  Eigen::VectorXd density;       ///< P_k, (unit)^2 / Hz
  double sample_rate_hz = 0.0;
  double resolution_hz = 0.0;  ///< fs / L, the bin spacing
  double enbw_hz = 0.0;        ///< equivalent noise bandwidth fs S2 / S1^2 [Hz]
  int segment_length = 0;
  int segments = 0;  ///< K, the number of averaged segments
  int step = 0;      ///< samples between segment starts
  Window window = Window::Hann;
};

/// Welch PSD of x (see above). Throws std::invalid_argument for a non-positive sample rate,
/// non-finite samples, an overlap outside [0, 1), a segment shorter than the window needs
/// (rectangular 1, Hann 2, flat top 5) or a record shorter than one segment.
PowerSpectralDensity welch_psd(const Eigen::Ref<const Eigen::VectorXd>& x, double sample_rate_hz,
                               const WelchOptions& options = {});

/// Integral of the PSD over all bins, sum_k P_k fs/L: the mean square of the signal (its
/// variance when the mean is zero).
double total_power(const PowerSpectralDensity& psd);

}  // namespace geardyn::signal
