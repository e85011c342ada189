#pragma once
// Frequency weightings A and C of sound level meters (docs/theory.md §14), from the analytic
// transfer functions of IEC 61672-1:2013 "Electroacoustics - Sound level meters - Part 1:
// Specifications", Annex E: with the pole frequencies f1 = 20.598997, f2 = 107.65265,
// f3 = 737.86223, f4 = 12194.217 Hz,
//   R_C(f) = f4^2 f^2 / ((f^2 + f1^2)(f^2 + f4^2))
//   R_A(f) = f4^2 f^4 / ((f^2 + f1^2) sqrt((f^2 + f2^2)(f^2 + f3^2)) (f^2 + f4^2))
// and the gains A(f) = 20 lg(R_A(f) / R_A(1 kHz)), C(f) = 20 lg(R_C(f) / R_C(1 kHz)) in dB, so
// that both are exactly 0 dB at 1 kHz (the standard's constants A1000 = -2.000 dB and
// C1000 = -0.062 dB are these normalisations rounded).
namespace geardyn::signal {

enum class Weighting {
  Z,  ///< zero (flat) weighting: 0 dB everywhere
  A,
  C
};

/// Gain of weighting `w` at frequency f [Hz] in dB (0 at 1 kHz). Throws std::invalid_argument
/// for f <= 0 or non-finite f.
double weighting_db(Weighting w, double frequency_hz);

/// The same as a factor on power, 10^(gain/10).
double weighting_power_factor(Weighting w, double frequency_hz);

}  // namespace geardyn::signal
