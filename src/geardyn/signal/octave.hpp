#pragma once
// One-third-octave bands, base 10 (IEC 61260-1:2014 "Electroacoustics - Octave-band and
// fractional-octave-band filters - Part 1: Specifications", sections 5.2-5.6 and Annex E;
// docs/theory.md §14): octave ratio G = 10^(3/10), exact mid-band frequencies
// f_m = 1000 G^(x/3) Hz for integer x, band edges f_1,2 = f_m G^(-+1/6). The nominal labels
// (25, 31.5, ... 20000 Hz) are the standard's rounded names of the exact f_m.
//
// Band powers are computed from a one-sided spectrum on uniform bins: bin k stands for the
// interval [f_k - df/2, f_k + df/2] and its power is shared among the bands in proportion to the
// overlap (ideal band-pass filters with the standard's exact edges, not a class-1 filter's skirts).
#include <Eigen/Dense>
#include <vector>

namespace geardyn::signal {

struct OctaveBand {
  double nominal_hz = 0.0;  ///< label, e.g. 31.5
  double mid_hz = 0.0;      ///< exact f_m = 1000 G^(x/3)
  double lower_hz = 0.0;    ///< f_m G^(-1/6)
  double upper_hz = 0.0;    ///< f_m G^(+1/6)
};

/// The 1/3-octave bands with nominal mid frequencies 25 Hz ... 20 kHz (x = -16 ... 13), in
/// ascending order.
std::vector<OctaveBand> third_octave_bands();

/// Power in each band from the power of uniform bins: frequency_hz[k] = k df (df > 0, first bin
/// at 0), bin_power[k] in unit^2 (for a PSD: P_k df; for a 0-peak amplitude spectrum: A_k^2/2,
/// DC A_0^2). Throws std::invalid_argument for sizes that differ, fewer than 2 bins, a
/// non-uniform axis or negative powers.
Eigen::VectorXd band_powers(const std::vector<OctaveBand>& bands,
                            const Eigen::Ref<const Eigen::VectorXd>& frequency_hz,
                            const Eigen::Ref<const Eigen::VectorXd>& bin_power);

/// Power of each bin of a one-sided 0-peak amplitude spectrum (signal/spectrum.hpp): A_k^2/2,
/// except DC (A_0^2) and, for an even record length n, the Nyquist bin (A_{n/2}^2).
Eigen::VectorXd bin_power_from_amplitude(const Eigen::Ref<const Eigen::VectorXd>& amplitude,
                                         int samples);

/// Level in dB of a power (mean square) re the square of a reference: 10 lg(power / ref^2).
/// Returns -infinity for zero power.
double power_level_db(double power, double reference);

}  // namespace geardyn::signal
