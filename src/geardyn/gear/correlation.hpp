#pragma once
// Correlation of a computed forced response with a measured one (speed or frequency sweeps):
// peak position, peak amplitude and quality factor Q by the half-power method, and the scaling
// of the harmonic mesh force that makes the computed peak match the measured one.
// Reference: A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped
// with Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 5.2 (linear response
// amplitude validation: resonance amplitudes scaled to the measured ones, the scale factor
// giving the harmonic excitation; the resonance amplitude depends on torque, Q and contact
// ratio). Half-power method: Ewins, Modal Testing, 2nd ed., sec. 4.3 (signal/half_power.hpp).
//
// Measured-response CSV (comma separated; '#' comments and blank lines ignored; header first):
//   abscissa: speed_rpm or frequency_hz (exactly one; strictly increasing, >= 0)
//   amplitude_<unit>: m, mm, um, nm (displacement); m_s, mm_s (velocity); m_s2, g
//     (acceleration); n (force); strain, ustrain; pa, mpa (stress). Values >= 0.
//   optional phase_deg.
// Example:
//   # strain gauge SG3, engine order 23
//   speed_rpm, amplitude_ustrain, phase_deg
//   4000, 12.1, -3.0
#include <cstddef>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/table.hpp"

namespace geardyn::gear {

enum class ResponseAbscissa { SpeedRpm, FrequencyHz };

/// A measured amplitude curve, amplitudes in SI units.
struct MeasuredResponse {
  std::string source;
  ResponseAbscissa abscissa = ResponseAbscissa::SpeedRpm;
  std::vector<double> x;          ///< speed [rpm] or frequency [Hz], strictly increasing
  std::vector<double> amplitude;  ///< in `amplitude_unit`
  std::string amplitude_unit;     ///< SI: "m", "m/s", "m/s^2", "N", "strain" or "Pa"
  std::vector<double> phase_deg;  ///< empty when the file has none
};

/// Parses the CSV above. InputError (file, line, column, column name) for a missing or unknown
/// column, a non-numeric or non-finite cell, a non-increasing abscissa, a negative amplitude or
/// fewer than 5 rows.
MeasuredResponse parse_measured_response_csv(std::string_view text, const std::string& file_name);
MeasuredResponse read_measured_response_csv(const std::filesystem::path& path);

/// One resonance peak of an amplitude curve.
struct PeakEstimate {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t index = 0;        ///< sample of the maximum
  double x = kNaN;              ///< peak abscissa (parabolic refinement)
  double amplitude = kNaN;      ///< peak amplitude (parabolic refinement)
  double x1 = kNaN, x2 = kNaN;  ///< half-power (A / sqrt 2) crossings, linearly interpolated
  double q_factor = kNaN;       ///< x / (x2 - x1); NaN when a crossing is outside the data
  double damping_ratio = kNaN;  ///< 1 / (2 Q)
  int points_in_band = 0;       ///< samples within [x1, x2] (few: Q is poorly resolved)
};

/// The peak of `amplitude(x)`: the highest interior local maximum, or (when `near` is given) the
/// local maximum closest to `near`. Throws InputError (key `response`) for mismatched sizes, a
/// non-increasing x, or a curve without an interior maximum.
PeakEstimate estimate_peak(std::span<const double> x, std::span<const double> amplitude,
                           double near = PeakEstimate::kNaN);

/// Measured versus computed peak. Mismatches are relative to the measurement:
/// (computed - measured) / measured.
struct PeakComparison {
  PeakEstimate measured, computed;
  double x_mismatch = PeakEstimate::kNaN;
  double amplitude_mismatch = PeakEstimate::kNaN;
  double q_mismatch = PeakEstimate::kNaN;
};

struct CorrelationOptions {
  double min_prominence_db = 6.0;  ///< measured peaks at least this prominent (20 log10 A)
  std::size_t max_peaks = 8;       ///< at most this many (the most prominent), sorted by x
};

/// Every prominent measured peak matched with the computed local maximum nearest in x
/// (computed curve on its own abscissa, same unit as the measured one).
std::vector<PeakComparison> compare_peaks(std::span<const double> measured_x,
                                          std::span<const double> measured_amplitude,
                                          std::span<const double> computed_x,
                                          std::span<const double> computed_amplitude,
                                          const CorrelationOptions& options = {});

/// Table `name`: peak, measured_/computed_<speed_rpm|frequency_hz>, x_mismatch_pct,
/// measured_/computed_amplitude_<unit>, amplitude_mismatch_pct, measured_q, computed_q,
/// q_mismatch_pct. `amplitude_unit` as in MeasuredResponse.
Table correlation_table(const std::vector<PeakComparison>& peaks, ResponseAbscissa abscissa,
                        const std::string& amplitude_unit, std::string name = "correlation");

/// Scaling of a linear response to a measured peak: scale = A_measured / A_computed, and the
/// harmonic force that reproduces the measurement, implied_force_n = scale * force_used_n.
struct ForceScaling {
  double scale = PeakEstimate::kNaN;
  double implied_force_n = PeakEstimate::kNaN;
};
/// Throws InputError for a non-positive force or a comparison without both amplitudes.
ForceScaling scale_force_to_peak(const PeakComparison& peak, double force_used_n);

}  // namespace geardyn::gear
