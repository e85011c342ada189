// The effective filter response of signal/octave's 1/3-octave band levels (band_powers of a
// windowed amplitude spectrum, ideal band edges) against the class-1 acceptance limits of
// IEC 61260-1:2014 "Electroacoustics - Octave-band and fractional-octave-band filters - Part 1:
// Specifications", Table 1 (relative attenuation Delta A = A(Omega) - A(1) in dB at the
// normalised frequencies Omega = G^x of an octave band, x = 0, 1/8, 1/4, 3/8, 1/2 (just inside and
// just outside the edge), 1, 2, 3, 4, and their reciprocals), with the breakpoints of an octave
// band mapped to a 1/b-octave band by the standard's formula
//   Omega_b = 1 + (G^(1/(2b)) - 1) / (G^(1/2) - 1) (G^x - 1)   (and 1 / Omega_b below f_m).
// Class-1 limits (2014 edition), as transcribed in J. M. Requena-Plens, "phonometry"
// (filters/compliance.py, 2026): pass band -0.4 <= Delta A <= 0.4, 0.5, 0.7, 1.4, 5.3 at
// x = 0, 1/8, 1/4, 3/8, 1/2-; stop band Delta A >= 1.2, 16.6, 40.5, 60.0, 70.0 at x = 1/2+, 1, 2,
// 3, 4 (and beyond). Between the breakpoints the limits are interpolated linearly in lg Omega.
//
// The swept sine: a sine of fixed amplitude at f = Omega f_m, read through a Hann-windowed
// spectrum of n = 65536 samples at 48 kHz (0.73 Hz bins), bin powers A_k^2/2 and band_powers. The
// window's equivalent noise bandwidth scales every band alike and cancels in Delta A. Spectral
// summation meets the mask when the band is many bins wide (the 50 Hz band is 16 bins): the
// leakage of a Hann window past its main lobe (2 bins) is below -31 dB (F. J. Harris, "On the use
// of windows for harmonic analysis with the discrete Fourier transform", Proc. IEEE 66 (1978)
// 51-83), while the mask rises by 1.6 dB per bin at most there.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/signal/octave.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFs = 48000.0;
constexpr int kN = 65536;

const double kG = std::pow(10.0, 0.3);

struct Limit {
  double x;    // octave-band exponent
  double min;  // dB
  double max;  // dB (infinity in the stop band)
};

constexpr double kInf = std::numeric_limits<double>::infinity();
// IEC 61260-1:2014 Table 1, class 1 (see the header comment).
constexpr std::array<Limit, 5> kPass = {{{0.0, -0.4, 0.4},
                                         {0.125, -0.4, 0.5},
                                         {0.25, -0.4, 0.7},
                                         {0.375, -0.4, 1.4},
                                         {0.5, -0.4, 5.3}}};
constexpr std::array<Limit, 5> kStop = {
    {{0.5, 1.2, kInf}, {1.0, 16.6, kInf}, {2.0, 40.5, kInf}, {3.0, 60.0, kInf}, {4.0, 70.0, kInf}}};

double breakpoint(double x) {  // for b = 3, Omega >= 1
  return 1.0 +
         (std::pow(kG, 1.0 / 6.0) - 1.0) / (std::pow(kG, 0.5) - 1.0) * (std::pow(kG, x) - 1.0);
}

// The class-1 limits at Omega (either side), linear in lg Omega between breakpoints.
Limit mask(double omega) {
  const double w = omega < 1.0 ? 1.0 / omega : omega;
  const double edge = breakpoint(0.5);
  auto interpolate = [&](const auto& rows, bool use_max) {
    if (w >= breakpoint(rows.back().x)) return use_max ? rows.back().max : rows.back().min;
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
      const double a = breakpoint(rows[i].x);
      const double b = breakpoint(rows[i + 1].x);
      if (w >= a && w <= b) {
        const double s = std::log10(w / a) / std::log10(b / a);
        const double lo = use_max ? rows[i].max : rows[i].min;
        const double hi = use_max ? rows[i + 1].max : rows[i + 1].min;
        return lo + s * (hi - lo);
      }
    }
    return use_max ? rows.front().max : rows.front().min;
  };
  if (w <= edge) return {0.0, kPass.front().min, interpolate(kPass, true)};
  return {0.0, interpolate(kStop, false), kInf};
}

// Band powers of all 1/3-octave bands for a unit sine at f.
Eigen::VectorXd band_levels_of_sine(double f, const std::vector<OctaveBand>& bands) {
  Eigen::VectorXd x(kN);
  for (int j = 0; j < kN; ++j) x[j] = std::cos(2 * kPi * f * j / kFs + 0.3);
  const AmplitudeSpectrum s = amplitude_spectrum(x, kFs, Window::Hann);
  return band_powers(bands, s.frequency_hz, bin_power_from_amplitude(s.amplitude, kN));
}

TEST(OctaveFilterMask, SpectralSummationMeetsIec61260Class1) {
  const std::vector<OctaveBand> all = third_octave_bands();
  std::vector<OctaveBand> bands;  // 50 Hz ... 4 kHz: at least 16 bins wide, G^4 below Nyquist
  for (const OctaveBand& b : all)
    if (b.nominal_hz >= 50.0 && b.nominal_hz <= 4000.0) bands.push_back(b);
  const auto nb = static_cast<Eigen::Index>(bands.size());
  Eigen::VectorXd reference(nb);  // A(1): each band's power for the sine at its own f_m
  for (Eigen::Index b = 0; b < nb; ++b)
    reference[b] = band_levels_of_sine(bands[static_cast<std::size_t>(b)].mid_hz, bands)[b];

  int checked = 0;
  double worst_margin = kInf;
  auto check = [&](Eigen::Index b, double omega, double power) {
    const double ratio = power / reference[b];
    const double delta_a = ratio > 0.0 ? -10.0 * std::log10(ratio) : kInf;
    const Limit lim = mask(omega);
    const double nominal = bands[static_cast<std::size_t>(b)].nominal_hz;
    EXPECT_GE(delta_a, lim.min) << "band " << nominal << " Hz, Omega " << omega;
    EXPECT_LE(delta_a, lim.max) << "band " << nominal << " Hz, Omega " << omega;
    worst_margin = std::min({worst_margin, delta_a - lim.min, lim.max - delta_a});
    ++checked;
  };

  // The tabulated normalised frequencies of each band (both sides; just inside and just
  // outside the edges).
  std::vector<double> omegas;
  for (const Limit& l : kPass) omegas.push_back(breakpoint(l.x) * (l.x == 0.5 ? 1 - 1e-9 : 1.0));
  for (const Limit& l : kStop) omegas.push_back(breakpoint(l.x) * (l.x == 0.5 ? 1 + 1e-9 : 1.0));
  const std::size_t tabulated = omegas.size();
  for (std::size_t i = 1; i < tabulated; ++i) omegas.push_back(1.0 / omegas[i]);
  for (Eigen::Index b = 0; b < nb; ++b) {
    const double fm = bands[static_cast<std::size_t>(b)].mid_hz;
    for (double omega : omegas)
      if (omega * fm <= 0.45 * kFs) check(b, omega, band_levels_of_sine(omega * fm, bands)[b]);
  }
  // A sweep in steps of 1/48 octave (G^(1/48)) from 20 Hz to 0.45 fs: the mid frequencies are
  // 1000 G^(x/3) Hz, so every band sees Omega = G^(i/48) and one sine serves all bands.
  for (int i = -272; 1000.0 * std::pow(kG, i / 48.0) <= 0.45 * kFs; ++i) {
    const double f = 1000.0 * std::pow(kG, i / 48.0);
    const Eigen::VectorXd p = band_levels_of_sine(f, bands);
    for (Eigen::Index b = 0; b < nb; ++b)
      check(b, f / bands[static_cast<std::size_t>(b)].mid_hz, p[b]);
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GE(worst_margin, 0.0);
  RecordProperty("worst_margin_db", std::to_string(worst_margin));
  RecordProperty("points_checked", checked);
}

}  // namespace
}  // namespace geardyn::signal
