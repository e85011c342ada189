#include "geardyn/signal/weighting.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace geardyn::signal {
namespace {

// IEC 61672-1:2013, Annex E, equations (E.1)-(E.6).
constexpr double kF1 = 20.598997;
constexpr double kF2 = 107.65265;
constexpr double kF3 = 737.86223;
constexpr double kF4 = 12194.217;

double response_c(double f) {
  const double f2 = f * f;
  return kF4 * kF4 * f2 / ((f2 + kF1 * kF1) * (f2 + kF4 * kF4));
}

double response_a(double f) {
  const double f2 = f * f;
  return kF4 * kF4 * f2 * f2 /
         ((f2 + kF1 * kF1) * std::sqrt((f2 + kF2 * kF2) * (f2 + kF3 * kF3)) * (f2 + kF4 * kF4));
}

}  // namespace

double weighting_db(Weighting w, double frequency_hz) {
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz))
    throw std::invalid_argument("weighting: frequency must be positive and finite, got " +
                                std::to_string(frequency_hz) + " Hz");
  switch (w) {
    case Weighting::Z:
      return 0.0;
    case Weighting::A:
      return 20.0 * std::log10(response_a(frequency_hz) / response_a(1000.0));
    case Weighting::C:
      return 20.0 * std::log10(response_c(frequency_hz) / response_c(1000.0));
  }
  throw std::invalid_argument("weighting: unknown weighting");
}

double weighting_power_factor(Weighting w, double frequency_hz) {
  return std::pow(10.0, weighting_db(w, frequency_hz) / 10.0);
}

}  // namespace geardyn::signal
