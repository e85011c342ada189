// 1/3-octave bands (base 10) vs IEC 61260-1:2014 "Electroacoustics - Octave-band and
// fractional-octave-band filters - Part 1: Specifications", Annex E Table E.1 (exact mid-band
// frequencies to five significant figures), and band powers from spectra.
#include "geardyn/signal/octave.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "geardyn/signal/psd.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ThirdOctaveBands, MidFrequenciesMatchIec61260TableE1) {
  // Table E.1, exact mid-band frequencies (base 10) printed to five significant figures.
  constexpr std::array<double, 30> kExact = {
      25.119, 31.623, 39.811, 50.119, 63.096, 79.433, 100.00, 125.89, 158.49, 199.53,
      251.19, 316.23, 398.11, 501.19, 630.96, 794.33, 1000.0, 1258.9, 1584.9, 1995.3,
      2511.9, 3162.3, 3981.1, 5011.9, 6309.6, 7943.3, 10000,  12589,  15849,  19953};
  const std::vector<OctaveBand> bands = third_octave_bands();
  ASSERT_EQ(bands.size(), kExact.size());
  for (std::size_t i = 0; i < bands.size(); ++i) {
    // Five significant figures: half a unit of the last digit, 5e-5 relative at most.
    EXPECT_NEAR(bands[i].mid_hz / kExact[i], 1.0, 5e-5) << bands[i].nominal_hz;
    // Edges f_m G^(-+1/6): the band is 10^(0.1) = 1.2589 wide and f_m is their geometric mean.
    EXPECT_NEAR(bands[i].upper_hz / bands[i].lower_hz, std::pow(10.0, 0.1), 1e-12);
    EXPECT_NEAR(std::sqrt(bands[i].upper_hz * bands[i].lower_hz) / bands[i].mid_hz, 1.0, 1e-12);
    if (i > 0) {
      EXPECT_NEAR(bands[i].lower_hz / bands[i - 1].upper_hz, 1.0, 1e-12);
    }
  }
  EXPECT_DOUBLE_EQ(bands.front().nominal_hz, 25.0);
  EXPECT_DOUBLE_EQ(bands[15].nominal_hz, 800.0);
  EXPECT_DOUBLE_EQ(bands.back().nominal_hz, 20000.0);
  EXPECT_NEAR(bands[16].mid_hz, 1000.0, 1e-9);
}

TEST(ThirdOctaveBands, SineAtABandCentreFallsInItsBandWithItsFullPower) {
  // A cosine of amplitude 2 at the 1 kHz band's centre, on a bin (fs = 51200 Hz, n = 51200:
  // 1 Hz bins). With a Hann window its leakage (bins 999..1001) lies well inside 891..1122 Hz,
  // and the density scaling (division by the window's power) makes the band hold A^2/2 = 2
  // exactly; nothing reaches another band. Exact to rounding: 1e-12.
  const double fs = 51200.0;
  const int n = 51200;
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j) x[j] = 2.0 * std::cos(2 * kPi * 1000.0 * j / fs);
  const PowerSpectralDensity p = welch_psd(x, fs, {.segment_length = n, .overlap = 0.0});
  const std::vector<OctaveBand> bands = third_octave_bands();
  const Eigen::VectorXd power = band_powers(bands, p.frequency_hz, p.density * p.resolution_hz);
  EXPECT_NEAR(power[16], 2.0, 1e-12);
  EXPECT_NEAR(power.sum(), 2.0, 1e-12);  // nothing in the other bands
  // The same from a rectangular amplitude spectrum: one bin of amplitude 2.
  const AmplitudeSpectrum a = amplitude_spectrum(x, fs, Window::Rectangular);
  const Eigen::VectorXd power_a =
      band_powers(bands, a.frequency_hz, bin_power_from_amplitude(a.amplitude, a.samples));
  EXPECT_NEAR(power_a[16], 2.0, 1e-12);
  EXPECT_NEAR(power_level_db(power_a[16], 1.0), 10 * std::log10(2.0), 1e-12);
}

TEST(ThirdOctaveBands, WhiteNoiseGivesBandPowerProportionalToBandwidth) {
  // White noise of variance sigma^2 sampled at fs has the flat one-sided density
  // sigma^2 / (fs/2), so a band of width B holds sigma^2 B / (fs/2). Welch estimate: 2^20
  // samples, 4096-sample Hann segments (4.9 Hz bins), 50 % overlap, ~500 independent segments:
  // a bin scatters by ~5 %. The bands from 250 Hz up span >= 12 bins (scatter < 1.5 %, and the
  // edge bins split proportionally); 10 % is more than six standard deviations.
  const double fs = 20000.0;
  const double sigma = 1.5;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::VectorXd x(1 << 20);
  for (int j = 0; j < x.size(); ++j) x[j] = normal(rng);
  const PowerSpectralDensity p = welch_psd(x, fs, {.segment_length = 4096, .overlap = 0.5});
  const std::vector<OctaveBand> bands = third_octave_bands();
  const Eigen::VectorXd power = band_powers(bands, p.frequency_hz, p.density * p.resolution_hz);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    if (bands[b].mid_hz < 240.0 || bands[b].upper_hz > fs / 2) continue;
    const double expected = sigma * sigma * (bands[b].upper_hz - bands[b].lower_hz) / (fs / 2);
    EXPECT_NEAR(power[static_cast<Eigen::Index>(b)] / expected, 1.0, 0.10) << bands[b].nominal_hz;
  }
}

TEST(ThirdOctaveBands, EdgeBinsAreSplitProportionally) {
  // One bin of power 1 at 10 Hz spacing whose interval straddles the 1 kHz band's lower edge
  // (891.25 Hz): bin 89 covers 885..895 Hz, 0.375 of it (891.25..895) inside the band.
  const std::vector<OctaveBand> bands = third_octave_bands();
  Eigen::VectorXd f(201);
  for (int k = 0; k <= 200; ++k) f[k] = 10.0 * k;
  Eigen::VectorXd pw = Eigen::VectorXd::Zero(201);
  pw[89] = 1.0;
  const Eigen::VectorXd power = band_powers(bands, f, pw);
  const double inside = (895.0 - bands[16].lower_hz) / 10.0;
  EXPECT_NEAR(power[16], inside, 1e-12);
  EXPECT_NEAR(power[15], 1.0 - inside, 1e-12);
  EXPECT_THROW(band_powers(bands, f, pw.head(10)), std::invalid_argument);
  pw[3] = -1.0;
  EXPECT_THROW(band_powers(bands, f, pw), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
