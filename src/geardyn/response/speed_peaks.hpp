#pragma once
// Parts shared by the forced responses over speed: the speed list check and the resonance peaks
// of an amplitude-versus-speed curve with their half-power quality factor.
//
// For one excitation order the excitation frequency is proportional to the speed, omega = c W,
// so the half-power band of a resonance measured in speed, Q = W_r / (W_2 - W_1), is the band
// measured in frequency (Q = omega_r / (omega_2 - omega_1) = 1 / (2 zeta) for a lightly damped,
// isolated mode) as long as the natural frequency does not change with speed across the band
// (rotors: gyroscopic and speed-dependent bearing terms make the two differ slightly).
// Reference: Ewins, Modal Testing, 2nd ed., 2000, sec. 4.3; A. Durastante, "Simulation of the
// Dynamic Response of Aeronautical Gears Equipped with Damper Rings", MSc thesis, Politecnico di
// Torino, 2018 (the damper-ring thesis), sec. 2.3.1, half-power Q-factor.
#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

namespace geardyn::response {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Throws InputError (key path `key`) unless `speeds` [rad/s] is non-empty, finite, positive and
/// strictly increasing.
void check_speeds(const Eigen::VectorXd& speeds, const std::string& key);

struct PeakOptions {
  /// A local maximum counts as a resonance peak when it stands at least this much above the
  /// higher of its two bases (topographic prominence), measured on 20 log10(amplitude) [dB].
  double min_prominence_db = 1.0;
  /// A peak's Q counts as resolved when both half-power crossings are found and the band holds at
  /// least this many samples (fewer: the linear interpolation of the crossings is too coarse).
  int min_points_in_band = 3;
  std::vector<std::string> validate() const;
};

/// One resonance peak of an amplitude-versus-speed curve.
struct SpeedPeak {
  int sensor = 0;
  int curve = 0;            ///< which response curve (e.g. excitation order); -1: a superposed sum
  double speed = kNaN;      ///< peak speed [rad/s], parabolic refinement of the sampled maximum
  double amplitude = kNaN;  ///< peak amplitude (refined), in the unit of the curve
  double speed1 = kNaN;     ///< lower half-power (amplitude / sqrt 2) crossing [rad/s]; NaN: none
  double speed2 = kNaN;     ///< upper crossing [rad/s]; NaN: none
  double q_factor = kNaN;   ///< speed / (speed2 - speed1); NaN when a crossing is missing
  int points_in_band = 0;   ///< samples inside [speed1, speed2]
  bool resolved = false;    ///< both crossings and >= PeakOptions::min_points_in_band samples
};

/// The resonance peaks of `amplitude(speeds)` (same length, amplitude >= 0), in increasing speed.
/// Zero amplitudes are floored at 1e-300 before taking decibels. Throws InputError for
/// mismatched sizes or invalid options.
std::vector<SpeedPeak> find_speed_peaks(const Eigen::VectorXd& speeds,
                                        const Eigen::VectorXd& amplitude, int sensor, int curve,
                                        const PeakOptions& options = {});

/// find_speed_peaks on every column (sensor) of `amplitude` (speeds x sensors), appended to
/// `peaks`.
void append_speed_peaks(std::vector<SpeedPeak>& peaks, const Eigen::VectorXd& speeds,
                        const Eigen::MatrixXd& amplitude, int curve, const PeakOptions& options);

}  // namespace geardyn::response
