// Welch PSD: density scaling and Parseval. References: P. D. Welch, "The use of fast Fourier
// transform for the estimation of power spectra", IEEE Trans. Audio Electroacoust. 15 (1967)
// 70-73; G. Heinzel, A. Ruediger, R. Schilling, "Spectrum and spectral density estimation by the
// Discrete Fourier transform (DFT)", 2002, sections 9-10 (PSD = |X|^2 2/(fs S2)).
#include "geardyn/signal/psd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::VectorXd white_noise(int n, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j) x[j] = normal(rng);
  return x;
}

TEST(WelchPsd, RectangularNonOverlappingIntegratesToTheMeanSquareExactly) {
  // Parseval per segment (DFT identity sum x^2 = (1/L) sum |X|^2): with a rectangular window and
  // segments tiling the record the integral of the PSD is the mean square of the samples, exact
  // to rounding (1e-10 relative covers the FFT's ~1e-15 per operation over 2^16 samples).
  const Eigen::VectorXd x = white_noise(1 << 16, 2.0, 7);
  const PowerSpectralDensity p =
      welch_psd(x, 1000.0, {.segment_length = 1024, .window = Window::Rectangular, .overlap = 0.0});
  EXPECT_EQ(p.segments, 64);
  EXPECT_EQ(p.density.size(), 513);
  EXPECT_DOUBLE_EQ(p.resolution_hz, 1000.0 / 1024);
  EXPECT_DOUBLE_EQ(p.enbw_hz, 1000.0 / 1024);
  const double mean_square = x.squaredNorm() / x.size();
  EXPECT_NEAR(total_power(p) / mean_square, 1.0, 1e-10);
}

TEST(WelchPsd, HannOverlappedIntegratesToTheVarianceWithinTheStatisticalBound) {
  // White Gaussian noise, sigma = 2: the true variance is 4 and the flat density sigma^2/(fs/2).
  // The estimate of the total power is an average of N = 2^17 squared samples (the Hann windows
  // with 50 % overlap weight every sample by w^2 summing to ~S2 per step): its relative standard
  // deviation is about sqrt(2/N) = 0.0039; 4 % is ten standard deviations.
  const double sigma = 2.0;
  const double fs = 2048.0;
  const Eigen::VectorXd x = white_noise(1 << 17, sigma, 11);
  const PowerSpectralDensity p = welch_psd(x, fs, {.segment_length = 512, .overlap = 0.5});
  EXPECT_EQ(p.step, 256);
  EXPECT_EQ(p.segments, (x.size() - 512) / 256 + 1);
  EXPECT_NEAR(p.enbw_hz, 1.5 * fs / 512, 1e-9);  // Hann ENBW 1.5 bins (Harris 1978, Table 1)
  EXPECT_NEAR(total_power(p) / (sigma * sigma), 1.0, 0.04);
  // The level: mean density over the interior bins vs sigma^2 / (fs / 2). Each bin averages
  // 511 segments (about 300 independent ones with 50 % Hann overlap, Welch 1967 Table 1), so a
  // bin scatters by ~6 % and the mean of 255 bins by under 0.5 %; 3 % is six standard deviations.
  const double level = p.density.segment(1, 255).mean();
  EXPECT_NEAR(level / (sigma * sigma / (fs / 2)), 1.0, 0.03);
}

TEST(WelchPsd, SineOfAmplitudeAHasPowerASquaredOverTwoInItsBand) {
  // x = A cos(2 pi f t): its power A^2/2 summed over the bins of its leakage. On a bin (f = 100
  // bins) the Hann leakage is exactly bins 99..101 and the sum is exact to rounding (1e-12). Off a
  // bin (100.37 bins) the Hann leakage beyond +-8 bins holds less than 1e-4 of the power
  // (sidelobes falling as 1/k^3, Harris 1978), and the segments are not whole periods: 1e-3.
  const double fs = 4096.0;
  const int L = 1024;
  const double amplitude = 3.0;
  for (const double bin : {100.0, 100.37}) {
    const double f = bin * fs / L;
    Eigen::VectorXd x(16 * L);
    for (int j = 0; j < x.size(); ++j) x[j] = amplitude * std::cos(2 * kPi * f * j / fs + 0.4);
    const PowerSpectralDensity p = welch_psd(x, fs, {.segment_length = L, .overlap = 0.5});
    const double band = p.density.segment(92, 17).sum() * p.resolution_hz;
    EXPECT_NEAR(band / (amplitude * amplitude / 2), 1.0, bin == 100.0 ? 1e-12 : 1e-3) << bin;
  }
}

TEST(WelchPsd, RejectsBadInput) {
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(100);
  EXPECT_THROW(welch_psd(x, 0.0, {.segment_length = 10}), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 100.0, {.segment_length = 200}), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 100.0, {.segment_length = 10, .overlap = 1.0}), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 100.0, {.segment_length = 1, .window = Window::Hann}),
               std::invalid_argument);
  Eigen::VectorXd bad = x;
  bad[3] = std::nan("");
  EXPECT_THROW(welch_psd(bad, 100.0, {.segment_length = 10}), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
