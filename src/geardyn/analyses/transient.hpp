#pragma once
// The transient analysis of docs/theory.md §6: the linear rotor model integrated in time at
// constant speed or through a linear run-up, driven by its unbalances, observed by its sensors.
//
//   model + fe::LinearSystem + TransientSettings
//     -> LinearRotorSystem (linear_rotor_system.hpp) -> integrate (integrator.hpp)
//     -> sensor time histories (every output_every step)
//     -> steady part (last steady_fraction of the record): Hann amplitude spectra (0-peak,
//        signal/spectrum.hpp) and orbits of the nodes with both ux and uy sensors.
// The record starts from rest (q = v = 0) at t = 0 with a consistent acceleration.
#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/signal/orbit.hpp"
#include "geardyn/transient/integrator.hpp"

namespace geardyn::analyses {

enum class Integrator { Newmark, GeneralizedAlpha };

struct TransientSettings : model::SettingsOf<TransientSettings> {
  double speed = 0.0;              ///< constant speed, or start of a run-up [rad/s]
  double speed_end = model::kNaN;  ///< run-up end speed (NaN: constant speed)
  double duration = model::kNaN;   ///< [s]
  double time_step = model::kNaN;  ///< [s]
  Integrator integrator = Integrator::GeneralizedAlpha;
  double rho_infinity = 0.9;            ///< spectral radius at infinity (generalised-alpha)
  double steady_fraction = 0.5;         ///< last fraction of the record used for spectra and orbits
  std::vector<std::string> unbalances;  ///< empty: all
  std::vector<std::string> sensors;     ///< empty: all
  int output_every = 1;                 ///< store every n-th step
};

/// Orbit of one node over the steady part, from its ux and uy sensor histories (node frame).
/// major / minor are the largest and smallest distances of the path from its centre (the middle
/// of its bounding box): the semi-axes for a single-frequency (elliptical) orbit, the extreme
/// excursions otherwise.
/// The whirl sense is relative to the node's spin (geometric sense about e3 times the sign of
/// its speed ratio; a non-spinning node counts the positive sense as forward).
struct TransientOrbit {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string node;
  int sensor_x = -1, sensor_y = -1;  ///< indices into TransientResult::sensor_names
  double major = kNaN;               ///< [m]
  double minor = kNaN;               ///< [m]
  signal::Whirl whirl = signal::Whirl::Straight;
  double speed_ratio = 0.0;
};

/// Is the steady part steady? The response of a linear system to unbalance at constant speed
/// settles to a sum of harmonics at the excitation frequencies order x speed. Over the steady
/// part every sensor is fitted (least squares) by a constant plus those harmonics; what remains
/// is the start-up transient (free vibration at the natural frequencies) or any other
/// non-synchronous content. The part is steady when that remainder's RMS is at most
/// kSteadyTolerance of the synchronous part's (for every sensor whose synchronous RMS is at
/// least 1e-3 of the largest of its unit): its orbits and spectra are then within about that
/// fraction of the steady state. The decay per revolution is from the remainder's RMS over the
/// first and second halves of the steady part.
struct Steadiness {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  static constexpr double kSteadyTolerance = 0.01;
  bool measured = false;          ///< false: run-up, no excitation, or too short (see `reason`)
  bool steady = false;            ///< measured and within kSteadyTolerance
  std::string reason;             ///< why not measured
  std::string sensor;             ///< the sensor with the largest non-synchronous fraction
  double non_synchronous = kNaN;  ///< RMS(remainder) / RMS(synchronous), that sensor
  /// Relative change of the remainder's RMS per revolution of the reference shaft (negative:
  /// decaying), from the two halves of the steady part.
  double change_per_revolution = kNaN;
  double revolutions = kNaN;  ///< in the steady part
  /// Estimate of the duration [s] at which the steady part would be steady (NaN: not
  /// decaying, or already steady).
  double duration_needed = kNaN;
};

struct TransientResult {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Status status = Status::Ok;
  std::string message;  ///< why status is not Ok, where, and what usually helps

  TransientSettings settings;     ///< as requested
  int steps = 0;                  ///< steps requested: ceil(duration / time_step)
  double sample_interval = kNaN;  ///< time_step x output_every [s]

  std::vector<std::string> sensor_names;
  std::vector<bool> sensor_rotational;  ///< rad (true) or m
  std::vector<int> sensor_equations;    ///< -1: constrained DOF, reads 0
  std::vector<double> time;             ///< stored samples [s]
  std::vector<double> speed;            ///< reference speed at each sample [rad/s]
  Eigen::MatrixXd values;               ///< samples x sensors [m or rad]

  int steady_first = 0;        ///< first sample of the steady part
  double steady_start = kNaN;  ///< its time [s]
  Eigen::VectorXd spectrum_frequency_hz;
  Eigen::MatrixXd spectrum_amplitude;  ///< bins x sensors, 0-peak, Hann, coherent-gain corrected
  double spectrum_resolution_hz = kNaN;
  std::vector<TransientOrbit> orbits;  ///< empty when the steady part is not steady
  Steadiness steadiness;

  transient::IntegrationSummary integration;
};

/// What a transient will cost, from its settings alone (known at check time).
struct TransientCost {
  static constexpr double kMaxSteps = 1e8;        ///< refused above
  static constexpr double kMaxOutputBytes = 2e9;  ///< time_history.csv refused above (2 GB)
  static constexpr double kBytesPerValue = 24.0;  ///< a shortest round-trip double and a comma
  double steps = 0.0;                             ///< ceil(duration / time_step)
  double samples = 0.0;       ///< stored: floor(steps / output_every) + 1 (t = 0)
  int columns = 0;            ///< time_s, speed_rpm and one per sensor
  double csv_bytes = 0.0;     ///< time_history.csv, about samples x columns x kBytesPerValue
  double memory_bytes = 0.0;  ///< the record in memory while it runs and is written (x 2)

  /// "8e+04 steps, 4e+04 stored samples x 6 columns: time_history.csv about 5.8 MB, 3.8 MB in
  /// memory".
  std::string describe() const;
  /// Empty when within the limits; else what is too large.
  std::string excess() const;
};

/// The cost of `settings` with `n_sensors` recorded sensors.
TransientCost estimate_cost(const TransientSettings& settings, int n_sensors);

/// Validates the settings (InputError naming the analysis key: non-positive duration or
/// time step, rho_infinity outside [0, 1], steady_fraction outside (0, 1], output_every < 1 or
/// above the number of steps, negative speeds, unknown unbalance or sensor names, a cost above
/// TransientCost's limits), builds the rotor system and integrates it. Numerical failures
/// (divergence, singular mass matrix) come back as a non-Ok status with the samples up to the
/// failure and no spectra or orbits. Measures the steadiness of the steady part (Steadiness); the
/// orbits are left out when it is not steady. Runs on the context's linear system and reports
/// progress per step to its progress.
TransientResult run_transient(const model::Model& model, const TransientSettings& settings,
                              const Context& context);

/// Tables "time_history" (time_s, speed_rpm, per sensor <name>_m or <name>_rad), "spectrum"
/// (frequency_hz, per sensor <name>_m or <name>_rad: 0-peak amplitude) and "orbits" (node,
/// major_m, minor_m, whirl; only when the steady part is steady, otherwise a note says why);
/// plots of the time histories (one per unit), the orbits (equal
/// aspect) and the spectra (log amplitude); notes on accuracy and the integrator's work.
AnalysisOutput transient_output(const model::Model& model, const TransientSettings& settings,
                                const TransientResult& result, const Context& context);

/// What a sweep reads of one sensor's record.
struct TransientSensorSummary {
  std::string unit;         ///< "m" or "rad"
  double peak = 0.0;        ///< largest |x(t)| over the whole record (start-up included)
  double peak_time = 0.0;   ///< [s] of that sample (the first of equal ones)
  double peak_speed = 0.0;  ///< reference speed at that sample [rad/s]
  double steady_rms = 0.0;  ///< sqrt(mean x^2) over the steady part
};

/// The summary of sensor `sensor`; std::runtime_error when the run did not record it or the
/// integration stopped early.
TransientSensorSummary summarize_sensor(const TransientResult& result, const std::string& sensor);

}  // namespace geardyn::analyses
