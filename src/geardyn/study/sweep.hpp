#pragma once
// Parameter sweep (study): one model value, addressed by its key path in the model file, is
// varied over a list; per point the model is rebuilt from the document, one analysis is run and
// scalar results are taken from its tables. Points run in parallel on threads; each point is
// independent and results are stored by index, so the output equals a serial run.
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model {
class ModelDocument;
}

namespace geardyn::study {

struct SweepResult {
  std::string parameter;
  std::vector<double> values;                ///< parameter values, in the key's units
  std::vector<std::string> labels;           ///< one per output
  std::vector<std::string> units;            ///< unit of each output column
  std::vector<std::vector<double>> outputs;  ///< outputs[j][i]: output j at point i (NaN: failed)
  std::vector<Status> point_status;
  std::vector<std::string> point_message;
  int threads_used = 1;
  Status status = Status::Ok;
  std::string message;
};

/// Runs the sweep. `threads` <= 0 uses all hardware threads.
SweepResult run_sweep(const model::ModelDocument& document, const model::SweepSettings& settings,
                      Progress& progress);

/// Scalar extracted from an analysis output per SweepOutput (public for tests). Returns NaN and
/// sets `unit`; throws InputError-free std::runtime_error when the output has no such data.
double extract_scalar(const AnalysisOutput& output, const model::SweepOutput& spec,
                      std::string& unit);

AnalysisOutput sweep_output(const SweepResult& result, const model::SweepSettings& settings,
                            const std::string& analysis_name);

}  // namespace geardyn::study
