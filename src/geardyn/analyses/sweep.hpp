#pragma once
// Parameter sweep (study): one model value, addressed by its key path in the model file, is
// varied over a list; per point the model is rebuilt from the document, one analysis is run and
// scalar results are taken from its tables. Points run in parallel on threads; each point is
// independent and results are stored by index, so the output equals a serial run.
#include <string>
#include <vector>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model {
class ModelDocument;
}

namespace geardyn::analyses {

/// A scalar result a sweep tabulates per point: one of the scalar outputs the target analysis's
/// type offers (registry.hpp, ScalarOutput).
struct SweepOutput {
  std::string quantity;     ///< a ScalarOutput name, e.g. "natural_frequency"
  int mode = 1;             ///< 1-based mode (natural_frequency, critical_speed)
  std::string sensor;       ///< peak_amplitude, peak_location, amplitude_at
  double at = model::kNaN;  ///< amplitude_at: speed or frequency [rad/s]
  bool at_speed = false;    ///< `at` is a speed (at_rpm) rather than a frequency (at_hz)
  std::string label;        ///< column name stem

  /// What this output asks of a result.
  ScalarRequest request() const { return {quantity, mode, sensor, at, at_speed}; }
};

struct SweepSettings : model::SettingsOf<SweepSettings> {
  std::string parameter;  ///< key path, e.g. "bearings[0].kxx" or "gear_meshes[0].stiffness"
  std::vector<std::string> linked_parameters;  ///< further key paths set to the same value
  std::vector<double> values;                  ///< in the units of the key
  std::string analysis;                        ///< name of the analysis run per point
  std::vector<SweepOutput> outputs;
  bool log_x = false;                    ///< plot with a log axis
  double reference_value = model::kNaN;  ///< deltas against this value's point (NaN: none)
  int threads = 0;                       ///< 0: all cores
};

struct SweepResult {
  std::string parameter;
  std::string parameter_unit;                ///< the key's unit as written ("N/m"; "" none)
  std::vector<double> values;                ///< parameter values, in the key's units
  std::vector<std::string> labels;           ///< one per output
  std::vector<std::string> units;            ///< unit of each output column
  std::vector<std::vector<double>> outputs;  ///< outputs[j][i]: output j at point i (NaN: failed)
  std::vector<Status> point_status;
  std::vector<std::string> point_message;
  int threads_used = 1;
  /// Why fewer threads ran than were asked for (empty when none): a BLAS that is not safe to
  /// call from several threads at once (linalg/blas_library.hpp).
  std::string thread_note;
  Status status = Status::Ok;
  std::string message;
};

/// Runs the sweep. `threads` <= 0 uses all hardware threads.
SweepResult run_sweep(const model::ModelDocument& document, const SweepSettings& settings,
                      Progress& progress);

/// The scalar `spec` of an analysis outcome through its type's `scalar`, with its unit;
/// std::runtime_error when the outcome has no such data.
double extract_scalar(const model::Analysis& analysis, const Outcome& outcome,
                      const SweepOutput& spec, std::string& unit);

AnalysisOutput sweep_output(const SweepResult& result, const SweepSettings& settings,
                            const std::string& analysis_name);

/// Table "sweep_deltas" (settings.reference_value given): each output minus its value at the
/// reference point (the swept value nearest reference_value), and for outputs that are not
/// levels in dB also the change in percent.
Table delta_table(const SweepResult& result, const SweepSettings& settings);

/// The driver shape of every analysis: the sweep of the model document the context carries
/// (NumericalError without one), and its output.
SweepResult run_sweep(const model::Model& model, const SweepSettings& settings,
                      const Context& context);
AnalysisOutput sweep_output(const model::Model& model, const SweepSettings& settings,
                            const SweepResult& result, const Context& context);

}  // namespace geardyn::analyses
