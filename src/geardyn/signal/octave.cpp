#include "geardyn/signal/octave.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace geardyn::signal {
namespace {

// IEC 61260-1:2014, Annex E, Table E.1: nominal mid-band frequencies of the 1/3-octave bands.
constexpr std::array<double, 30> kNominal = {
    25,  31.5, 40,   50,   63,   80,   100,  125,  160,  200,  250,  315,   400,   500,   630,
    800, 1000, 1250, 1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000, 20000};
constexpr int kFirstIndex = -16;  // x of the 25 Hz band

}  // namespace

std::vector<OctaveBand> third_octave_bands() {
  const double g = std::pow(10.0, 0.3);
  std::vector<OctaveBand> bands;
  bands.reserve(kNominal.size());
  for (std::size_t i = 0; i < kNominal.size(); ++i) {
    const double x = kFirstIndex + static_cast<double>(i);
    OctaveBand b;
    b.nominal_hz = kNominal[i];
    b.mid_hz = 1000.0 * std::pow(g, x / 3.0);
    b.lower_hz = b.mid_hz * std::pow(g, -1.0 / 6.0);
    b.upper_hz = b.mid_hz * std::pow(g, 1.0 / 6.0);
    bands.push_back(b);
  }
  return bands;
}

Eigen::VectorXd band_powers(const std::vector<OctaveBand>& bands,
                            const Eigen::Ref<const Eigen::VectorXd>& frequency_hz,
                            const Eigen::Ref<const Eigen::VectorXd>& bin_power) {
  const Eigen::Index n = frequency_hz.size();
  if (bin_power.size() != n)
    throw std::invalid_argument("band_powers: " + std::to_string(n) + " frequencies but " +
                                std::to_string(bin_power.size()) + " bin powers");
  if (n < 2) throw std::invalid_argument("band_powers: need at least 2 bins");
  const double df = frequency_hz[1] - frequency_hz[0];
  if (!(df > 0.0) || std::abs(frequency_hz[0]) > 1e-9 * df)
    throw std::invalid_argument("band_powers: the frequency axis must start at 0 Hz and increase");
  for (Eigen::Index k = 0; k < n; ++k) {
    if (std::abs(frequency_hz[k] - k * df) > 1e-6 * df)
      throw std::invalid_argument("band_powers: the frequency axis is not uniform at bin " +
                                  std::to_string(k));
    if (!(bin_power[k] >= 0.0))
      throw std::invalid_argument("band_powers: negative or non-finite power at bin " +
                                  std::to_string(k));
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(bands.size()));
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const double lo = bands[b].lower_hz;
    const double hi = bands[b].upper_hz;
    // Bins whose interval [k - 1/2, k + 1/2] df can overlap [lo, hi].
    const auto first = static_cast<Eigen::Index>(std::max(0.0, std::floor(lo / df - 0.5)));
    const auto last =
        std::min<Eigen::Index>(n - 1, static_cast<Eigen::Index>(std::ceil(hi / df + 0.5)));
    double sum = 0.0;
    for (Eigen::Index k = first; k <= last; ++k) {
      const double a = std::max(lo, (static_cast<double>(k) - 0.5) * df);
      const double c = std::min(hi, (static_cast<double>(k) + 0.5) * df);
      if (c > a) sum += bin_power[k] * (c - a) / df;
    }
    out[static_cast<Eigen::Index>(b)] = sum;
  }
  return out;
}

Eigen::VectorXd bin_power_from_amplitude(const Eigen::Ref<const Eigen::VectorXd>& amplitude,
                                         int samples) {
  if (amplitude.size() != samples / 2 + 1)
    throw std::invalid_argument("bin_power_from_amplitude: " + std::to_string(amplitude.size()) +
                                " amplitudes do not fit " + std::to_string(samples) + " samples");
  Eigen::VectorXd p = 0.5 * amplitude.cwiseAbs2();
  p[0] = amplitude[0] * amplitude[0];
  if (samples % 2 == 0) p[samples / 2] = amplitude[samples / 2] * amplitude[samples / 2];
  return p;
}

double power_level_db(double power, double reference) {
  if (!(reference > 0.0)) throw std::invalid_argument("power_level_db: reference must be positive");
  if (power <= 0.0) return -std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(power / (reference * reference));
}

}  // namespace geardyn::signal
