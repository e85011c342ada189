#pragma once
// Spectral windows for amplitude spectra (docs/theory.md §14).
//
// All windows are the periodic ("DFT-even") form: w_j for j = 0..n-1 is the first n samples of a
// symmetric window of length n + 1. That is the form whose DFT has its zeros exactly on the
// neighbouring bins, so an on-bin sinusoid reads its amplitude exactly after coherent-gain
// correction. Reference: F. J. Harris, "On the use of windows for harmonic analysis with the
// discrete Fourier transform", Proc. IEEE 66(1), 1978, pp. 51-83 (Table 1).
#include <Eigen/Dense>
#include <string_view>

namespace geardyn::signal {

enum class Window {
  Rectangular,  ///< w = 1; best resolution, scalloping loss up to 36 % between bins
  Hann,         ///< w = 0.5 (1 - cos(2 pi j / n)); scalloping loss up to 15.1 % (-1.42 dB)
  FlatTop       ///< 5-term flat top (SRS / MATLAB `flattopwin` coefficients); amplitude
                ///< error below 0.1 % anywhere between bins, wide main lobe (10 bins)
};

constexpr std::string_view to_string(Window w) {
  switch (w) {
    case Window::Rectangular:
      return "rectangular";
    case Window::Hann:
      return "hann";
    case Window::FlatTop:
      return "flattop";
  }
  return "rectangular";
}

/// The n coefficients of window `w` (periodic form). Throws std::invalid_argument for n < 1.
Eigen::VectorXd window_coefficients(Window w, int n);

/// Coherent gain sum(w) / n: the factor by which windowing scales a sinusoid's spectral peak.
/// Rectangular 1, Hann 0.5, flat top 0.21557895 (exact for the periodic form, n >= 5).
double coherent_gain(Window w, int n);

/// Equivalent noise bandwidth in bins, n sum(w^2) / sum(w)^2 (1, 1.5, 3.77).
double equivalent_noise_bandwidth(Window w, int n);

/// Largest amplitude error of a coherent-gain corrected sinusoid that falls between two bins
/// (half a bin off), as a fraction of the true amplitude, in the large-n limit:
/// rectangular 1 - 2/pi = 0.3634, Hann 1 - 8/(3 pi) = 0.1512, flat top 1.1e-3 (its worst point
/// is not half a bin off).
double max_scalloping_loss(Window w);

}  // namespace geardyn::signal
