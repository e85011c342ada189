#pragma once
// Waterfall (run-up Campbell diagram, docs/theory.md §14): short-time 0-peak amplitude spectra
// of a uniformly sampled time record, each block tagged with the mean shaft speed over it, and
// the order lines f = o n / 60 [Hz] (n in rpm) that an order-o component follows.
//
// The record x_j (n samples at fs) is cut into blocks of L samples starting `step` =
// L - round(overlap L) samples apart (as psd.hpp's segments); each block's spectrum is
// amplitude_spectrum (spectrum.hpp: coherent-gain corrected, an on-bin sinusoid reads its
// amplitude). The block's speed is its mean: from a shaft angle record theta(t), 60 (theta_end -
// theta_start) / (2 pi (t_end - t_start)) [rpm], exact for any speed profile; from a speed
// record, the mean of its samples over the block. A component whose frequency changes by
// delta_f during a block is smeared over delta_f / (fs / L) bins: with o the order, n' the run-up
// rate [rpm/s] and T = L / fs, delta_f = o n' T / 60; keep it below a few bins (the analysis
// order_analysis reports it). For a linear run-up a component's windowed spectrum is symmetric
// about the block's mid frequency, which is o times the mean speed.
// Reference: the short-time Fourier transform of J. B. Allen, "Short term spectral analysis,
// synthesis, and modification by discrete Fourier transform", IEEE Trans. Acoust. Speech Signal
// Process. 25 (1977) 235-238.
#include <Eigen/Dense>

#include "geardyn/signal/window.hpp"

namespace geardyn::signal {

struct WaterfallOptions {
  int block_length = 4096;  ///< L, samples per block (the DFT length): resolution fs / L
  double overlap = 0.5;     ///< fraction of L shared by consecutive blocks, 0 <= overlap < 1
  Window window = Window::Hann;
};

struct Waterfall {
  Eigen::VectorXd frequency_hz;  ///< k fs / L, k = 0 .. L/2
  Eigen::MatrixXd amplitude;     ///< (blocks x bins), 0-peak, in the unit of the signal
  Eigen::VectorXd speed_rpm;     ///< mean shaft speed of each block
  Eigen::VectorXd time_s;        ///< time at the middle of each block
  double sample_rate_hz = 0.0;
  double resolution_hz = 0.0;  ///< fs / L
  int block_length = 0;
  int step = 0;  ///< samples between block starts
  Window window = Window::Hann;
};

/// Sample rate of a uniformly sampled time axis, (n - 1) / (t_end - t_0). Throws
/// std::invalid_argument (naming the sample) when t has fewer than 2 samples, is not finite or
/// not strictly increasing, or a step differs from the mean step by more than 1e-6 of it.
double uniform_sample_rate(const Eigen::Ref<const Eigen::VectorXd>& time_s);

/// Waterfall of x with block speeds from the shaft angle record theta [rad] (same length as
/// t and x, increasing). Throws std::invalid_argument for sizes that differ, a time axis that
/// is not uniform, non-finite samples, a block shorter than the window needs, an overlap
/// outside [0, 1) or a record shorter than one block.
Waterfall waterfall_by_angle(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                             const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& angle_rad,
                             const WaterfallOptions& options = {});

/// Waterfall of x with block speeds the mean of the speed record [rpm] over each block.
Waterfall waterfall_by_speed(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                             const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& speed_rpm,
                             const WaterfallOptions& options = {});

/// The order line of order o over the speeds n [rpm]: f = o n / 60 [Hz].
Eigen::VectorXd order_line_hz(double order, const Eigen::Ref<const Eigen::VectorXd>& speed_rpm);

}  // namespace geardyn::signal
