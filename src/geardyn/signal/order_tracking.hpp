#pragma once
// Computed order tracking (docs/theory.md §14): a record x(t) sampled at times t_j is resampled
// to uniform steps of shaft angle, where a component of order o (o cycles per revolution) is a
// steady sinusoid whatever the speed, and analysed over blocks of whole revolutions.
// References: K. R. Fyfe, E. D. S. Munck, "Analysis of computed order tracking", Mechanical
// Systems and Signal Processing 11 (1997) 187-205; R. Potter, "A new order tracking method for
// rotating machinery", Sound and Vibration 24 (1990) 30-34.
//
// Angle: either a channel theta(t) [rad] (e.g. geardyn's shaft rotation record) or tacho pulses
// (pulses_per_revolution equally spaced pulses, angle 2 pi i / ppr at pulse i), interpolated
// between the pulses by a monotone piecewise cubic Hermite curve whose slopes are those of the
// parabola through three neighbouring pulses (exact for a constant angular acceleration) limited
// as in F. N. Fritsch, R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer.
// Anal. 17 (1980) 238-246, so the angle stays increasing.
// Resampling: the time of each uniform angle step by linear inversion of theta(t) between
// samples, then x at that time by four-point (cubic) Lagrange interpolation.
//
// Errors are std::invalid_argument with a message naming the column and the offending sample,
// for the caller to turn into a located error.
#include <Eigen/Dense>

#include "geardyn/signal/window.hpp"

namespace geardyn::signal {

/// Times of the rising crossings of `threshold` by a tacho signal (linear interpolation between
/// samples). Throws when t is not strictly increasing, sizes differ, or there is no crossing.
Eigen::VectorXd tacho_pulse_times(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                  const Eigen::Ref<const Eigen::VectorXd>& tacho, double threshold);

/// Shaft angle [rad] at the times t from pulse times (pulse i at angle 2 pi i / ppr). Samples
/// before the first or after the last pulse are extrapolated with the cubic of the end interval;
/// keep to the samples between the first and the last pulse for analysis. Throws for fewer than 2
/// pulses, non-increasing pulse times or t, or ppr < 1.
Eigen::VectorXd angle_from_pulse_times(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                       const Eigen::Ref<const Eigen::VectorXd>& pulse_times_s,
                                       int pulses_per_revolution);

/// A record on uniform shaft angle: angle_k = angle_0 + k 2 pi / samples_per_revolution.
struct AngleDomainRecord {
  Eigen::VectorXd angle_rad;
  Eigen::VectorXd time_s;  ///< time at which the shaft reached angle_k
  Eigen::VectorXd value;   ///< x at that time
  int samples_per_revolution = 0;
};

/// Resample x(t) to uniform angle from the angle channel theta(t) [rad], over
/// [theta_0, theta_end]. Throws when sizes differ, t or theta is not strictly increasing (the
/// message names the sample), values are not finite, samples_per_revolution < 4 or the record
/// is shorter than 4 samples.
AngleDomainRecord resample_to_angle(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                    const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const Eigen::Ref<const Eigen::VectorXd>& angle_rad,
                                    int samples_per_revolution);

/// Order spectra over consecutive blocks of `revolutions_per_block` whole revolutions.
struct OrderSpectra {
  Eigen::VectorXd order;      ///< k / revolutions_per_block, k = 0 .. n/2
  Eigen::MatrixXd amplitude;  ///< (blocks x orders), 0-peak, in the unit of the signal
  Eigen::VectorXd speed_rpm;  ///< mean speed of each block, 60 revolutions / block duration
  Eigen::VectorXd time_s;     ///< time at the middle of each block
  int revolutions_per_block = 0;
};

/// Amplitude spectra (signal/spectrum.hpp scaling) of the blocks; `overlap` in [0, 1) of a
/// block. Throws when the record holds less than one block.
OrderSpectra order_spectra(const AngleDomainRecord& record, int revolutions_per_block,
                           Window window = Window::Hann, double overlap = 0.0);

/// Order cuts: the 0-peak amplitude of each requested order in each block, from a windowed
/// single-frequency DFT at exactly that order (so orders off the block's order bins read
/// without picket-fence loss when the other components are on bins or far away).
struct OrderCuts {
  Eigen::VectorXd order;      ///< the requested orders
  Eigen::MatrixXd amplitude;  ///< (blocks x orders)
  Eigen::VectorXd speed_rpm;  ///< mean speed of each block
  Eigen::VectorXd time_s;     ///< time at the middle of each block
};

/// Throws when an order is negative or at/above the Nyquist order samples_per_revolution / 2,
/// or the record holds less than one block.
OrderCuts order_cuts(const AngleDomainRecord& record,
                     const Eigen::Ref<const Eigen::VectorXd>& orders, int revolutions_per_block,
                     Window window = Window::Hann, double overlap = 0.0);

}  // namespace geardyn::signal
