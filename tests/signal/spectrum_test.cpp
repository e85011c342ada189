// Amplitude spectrum: scaling convention (0-peak, DC not doubled), windows with coherent-gain
// correction, scalloping loss between bins, Parseval. The references are analytic: a sinusoid
// a cos(2 pi f t + phi) must read a on its bin (Harris 1978, Proc. IEEE 66(1):51, sections
// III-IV; coherent gain, ENBW and scalloping loss from its Table 1).
#include "geardyn/signal/spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::VectorXd sampled(int n, double fs, double mean, double amplitude, double frequency_hz,
                        double phase) {
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j)
    x[j] = mean + amplitude * std::cos(2 * kPi * frequency_hz * j / fs + phase);
  return x;
}

TEST(Window, CoherentGainAndNoiseBandwidthMatchHarrisTable) {
  // Harris Table 1: Hann CG 0.50, ENBW 1.50 bins; flat top CG = a0, ENBW 3.77 bins.
  EXPECT_NEAR(coherent_gain(Window::Rectangular, 64), 1.0, 1e-15);
  EXPECT_NEAR(coherent_gain(Window::Hann, 64), 0.5, 1e-15);
  EXPECT_NEAR(coherent_gain(Window::FlatTop, 64), 0.21557895, 1e-12);
  EXPECT_NEAR(equivalent_noise_bandwidth(Window::Rectangular, 64), 1.0, 1e-15);
  EXPECT_NEAR(equivalent_noise_bandwidth(Window::Hann, 64), 1.5, 1e-12);
  EXPECT_NEAR(equivalent_noise_bandwidth(Window::FlatTop, 64), 3.77, 0.005);
  // Hann is 0 at j = 0 and 1 at j = n/2 (periodic form).
  const Eigen::VectorXd hann = window_coefficients(Window::Hann, 8);
  EXPECT_NEAR(hann[0], 0.0, 1e-15);
  EXPECT_NEAR(hann[4], 1.0, 1e-15);
  EXPECT_THROW(window_coefficients(Window::Hann, 0), std::invalid_argument);
}

TEST(Window, ScallopingLossMatchesClosedForms) {
  // Half a bin off: rectangular |sinc(1/2)| = 2/pi, Hann 8/(3 pi) (Harris Table 1: 3.92 dB and
  // 1.42 dB); the flat top is flat to about 0.01 dB (1.1e-3).
  EXPECT_NEAR(max_scalloping_loss(Window::Rectangular), 1.0 - 2.0 / kPi, 1e-14);
  EXPECT_NEAR(max_scalloping_loss(Window::Hann), 1.0 - 8.0 / (3.0 * kPi), 1e-14);
  EXPECT_NEAR(20 * std::log10(1.0 - max_scalloping_loss(Window::Hann)), -1.42, 0.005);
  EXPECT_LT(max_scalloping_loss(Window::FlatTop), 1.2e-3);
}

TEST(FrequencyAxis, BinsAreMultiplesOfTheResolution) {
  const Eigen::VectorXd f = frequency_axis(10, 1000.0);
  ASSERT_EQ(f.size(), 6);
  EXPECT_DOUBLE_EQ(f[1], 100.0);
  EXPECT_DOUBLE_EQ(f[5], 500.0);  // Nyquist for even n
  EXPECT_EQ(frequency_axis(11, 1000.0).size(), 6);
  EXPECT_THROW(frequency_axis(10, 0.0), std::invalid_argument);
}

TEST(AmplitudeSpectrum, OnBinSinusoidReadsItsAmplitudeForEveryWindow) {
  // x = 1.2 + 3.7 cos(2 pi 50 t + 0.3), fs = 1000 Hz, n = 1000: 50 Hz is bin 50.
  const int n = 1000;
  const double fs = 1000.0;
  const Eigen::VectorXd x = sampled(n, fs, 1.2, 3.7, 50.0, 0.3);
  for (Window w : {Window::Rectangular, Window::Hann, Window::FlatTop}) {
    const AmplitudeSpectrum s = amplitude_spectrum(x, fs, w);
    ASSERT_EQ(s.amplitude.size(), n / 2 + 1);
    EXPECT_DOUBLE_EQ(s.frequency_hz[50], 50.0);
    // Rounding only: the sums run over 1000 terms of size ~4.
    EXPECT_NEAR(s.amplitude[50], 3.7, 1e-12) << to_string(w);
    EXPECT_NEAR(s.amplitude[0], 1.2, 1e-12) << to_string(w) << ": the mean is not doubled";
    EXPECT_NEAR(s.amplitude[200], 0.0, 1e-12) << to_string(w);
  }
  // Rectangular, on-bin: the phase is the cosine phase at t = 0.
  EXPECT_NEAR(amplitude_spectrum(x, fs, Window::Rectangular).phase[50], 0.3, 1e-12);
}

TEST(AmplitudeSpectrum, NyquistBinIsNotDoubled) {
  // x_j = 2 (-1)^j is a cosine at fs/2 with amplitude 2.
  const int n = 64;
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j) x[j] = (j % 2 == 0) ? 2.0 : -2.0;
  EXPECT_NEAR(amplitude_spectrum(x, 1.0, Window::Rectangular).amplitude[n / 2], 2.0, 1e-13);
}

TEST(AmplitudeSpectrum, HannOffBinStaysWithinScallopingLoss) {
  // A sinusoid delta bins off a bin centre: the largest bin near it must lie between
  // a (1 - max scalloping loss) and a; half a bin off it equals the closed form
  // a 8 / (3 pi) up to finite-n terms (the image at -f and the 1/n^2 Dirichlet correction,
  // both below 1e-5 here).
  const int n = 4096;
  const double fs = 4096.0;  // 1 Hz bins
  const double a = 0.25;
  const double loss = max_scalloping_loss(Window::Hann);
  for (double delta : {0.1, 0.25, 0.4, 0.5}) {
    const double f = 300.0 + delta;
    const AmplitudeSpectrum s = amplitude_spectrum(sampled(n, fs, 0.0, a, f, 1.0), fs);
    const double peak = std::max(s.amplitude[300], s.amplitude[301]);
    EXPECT_LE(peak, a * (1 + 1e-12)) << "delta " << delta;
    EXPECT_GE(peak, a * (1 - loss) * (1 - 1e-5)) << "delta " << delta;
    if (delta == 0.5) {
      EXPECT_NEAR(peak / a, 8.0 / (3.0 * kPi), 1e-5);
    }
  }
}

TEST(AmplitudeSpectrum, FlatTopOffBinReadsTheAmplitudeWithinItsFlatness) {
  const int n = 4096;
  const double fs = 4096.0;
  for (double delta : {0.0, 0.2, 0.5}) {
    const AmplitudeSpectrum s =
        amplitude_spectrum(sampled(n, fs, 0.0, 1.0, 500.0 + delta, 0.0), fs, Window::FlatTop);
    const double peak = std::max(s.amplitude[500], s.amplitude[501]);
    EXPECT_NEAR(peak, 1.0, max_scalloping_loss(Window::FlatTop) + 1e-5) << "delta " << delta;
  }
}

TEST(AmplitudeSpectrum, ParsevalHoldsForTheRectangularWindow) {
  // mean(x^2) = A_0^2 + sum_{0<k<n/2} A_k^2 / 2 + A_{n/2}^2 (n even); for odd n no Nyquist bin.
  std::mt19937 rng(2024);
  std::normal_distribution<double> normal(0.5, 2.0);
  for (int n : {1024, 1023}) {
    Eigen::VectorXd x(n);
    for (int j = 0; j < n; ++j) x[j] = normal(rng);
    const AmplitudeSpectrum s = amplitude_spectrum(x, 100.0, Window::Rectangular);
    double power = s.amplitude[0] * s.amplitude[0];
    const int last = static_cast<int>(s.amplitude.size()) - 1;
    for (int k = 1; k <= last; ++k) {
      const bool nyquist = (n % 2 == 0 && k == last);
      power += nyquist ? s.amplitude[k] * s.amplitude[k] : 0.5 * s.amplitude[k] * s.amplitude[k];
    }
    EXPECT_NEAR(power, x.squaredNorm() / n, 1e-12 * x.squaredNorm() / n) << "n = " << n;
  }
}

TEST(AmplitudeSpectrum, RejectsBadInput) {
  EXPECT_THROW(amplitude_spectrum(Eigen::VectorXd(), 1.0), std::invalid_argument);
  EXPECT_THROW(amplitude_spectrum(Eigen::VectorXd::Ones(8), -1.0), std::invalid_argument);
  EXPECT_THROW(amplitude_spectrum(Eigen::VectorXd::Ones(3), 1.0, Window::FlatTop),
               std::invalid_argument);
  Eigen::VectorXd bad = Eigen::VectorXd::Ones(8);
  bad[3] = std::nan("");
  EXPECT_THROW(amplitude_spectrum(bad, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
