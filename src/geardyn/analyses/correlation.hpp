#pragma once
// correlation: where the resonance peaks of a measured response lie, how sharp they are (Q),
// and how they compare with a reference (computed) peak.
//
// Resonance peaks of a measured response, Q by the half-power method with interpolated
// crossings, and the comparison with a reference peak (docs/theory.md §14; issue
// [mesh-excitation]): run_correlation finds the peaks (CorrelationResult), correlation_output
// writes the peak table (core/peak_table.hpp), the comparison, the plot and notes. Bad input throws
// InputError (call check_gear_pairs and the type's own input check, through analyses::check_inputs,
// before running, so it shows before any result); a numerical failure throws NumericalError naming
// the analysis.
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// A measured response curve: resonance peaks, Q by the half-power method, optional reference.
struct CorrelationSettings : model::SettingsOf<CorrelationSettings> {
  std::string measured_file;  ///< as written (relative to the model file)
  double min_prominence_db = 6.0;
  int max_peaks = 8;
  double reference_peak = model::kNaN;  ///< reference peak position [rad/s] (speed or frequency)
  bool reference_is_speed = true;  ///< reference_peak is a speed (rpm key) or frequency (hz key)
  double reference_amplitude = model::kNaN;  ///< in the measured file's SI amplitude unit
  double reference_q = model::kNaN;
};

/// The measured curve, its peaks in the order of their location, and the comparison.
struct CorrelationResult {
  gear::MeasuredResponse measured;
  std::vector<gear::PeakEstimate> peaks;           ///< location in the file's unit (rpm or Hz)
  std::vector<double> prominence_db;               ///< of each peak, in dB of the amplitude
  std::optional<gear::PeakComparison> comparison;  ///< with reference_peak_*
};

CorrelationResult run_correlation(const model::Model& model, const CorrelationSettings& settings,
                                  const Context& context);

AnalysisOutput correlation_output(const model::Model& model, const CorrelationSettings& settings,
                                  const CorrelationResult& result, const Context& context);

/// Checks made before anything runs: the measured file exists and reads, and its abscissa fits
/// the reference key (reference_peak_rpm or _hz). InputError.
void check_correlation_inputs(const model::Model& model, const CorrelationSettings& settings,
                              const Context& context);

}  // namespace geardyn::analyses
