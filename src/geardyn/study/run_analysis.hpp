#pragma once
// Runs one analysis of a model: (model, analysis settings) -> AnalysisOutput (tables, plots,
// status). No global state, so a study can run many of these on threads.
#include <functional>
#include <string>

#include "geardyn/component/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model {
class ModelDocument;
}

namespace geardyn::study {

/// What an analysis may need beyond the model: the document it came from (a sweep re-builds
/// the model per point from it).
struct RunContext {
  const model::ModelDocument* document = nullptr;
  Progress* progress = nullptr;  ///< null: silent
  /// Solid components built before the run (component::build_solids); null: an analysis that
  /// needs one builds it.
  const component::SolidComponents* solids = nullptr;
};

/// Runs `analysis` on `model` whose matrices are `system`. Numerical failures are caught and
/// returned as a non-Ok status with the message; InputError propagates (bad input).
AnalysisOutput run_analysis(const model::Model& model, const fe::LinearSystem& system,
                            const model::Analysis& analysis, const RunContext& context);

/// Type name used in the model file and the manifest ("modal", "campbell", ...).
std::string analysis_type_name(model::AnalysisType type);

}  // namespace geardyn::study
