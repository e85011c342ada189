#include "geardyn/analyses/registry.hpp"

#include <stdexcept>

namespace geardyn::analyses {

// Each analysis type's registry entry, defined in its <type>_entry.cpp.
// The list: one line per analysis type, in the order of the reference (docs/model-reference.md).
#define GEARDYN_ANALYSIS_TYPES(X) \
  X(modal)                        \
  X(campbell)                     \
  X(harmonic)                     \
  X(unbalance)                    \
  X(transient)                    \
  X(sweep)                        \
  X(solid_modal)                  \
  X(cyclic_modal)                 \
  X(reduction)                    \
  X(gear_pair)                    \
  X(tooth_contact)                \
  X(mesh_force)                   \
  X(mesh_harmonics)               \
  X(order_analysis)               \
  X(correlation)                  \
  X(cyclic_forced_response)       \
  X(gear_forced_response)         \
  X(gear_whine)                   \
  X(damper_ring_response)         \
  X(nonlinear_response)           \
  X(nonlinear_modes)              \
  X(drivetrain_transient)

#define GEARDYN_DECLARE_ANALYSIS(type) AnalysisType type##_analysis();
GEARDYN_ANALYSIS_TYPES(GEARDYN_DECLARE_ANALYSIS)
#undef GEARDYN_DECLARE_ANALYSIS

const std::vector<AnalysisType>& registry() {
#define GEARDYN_LIST_ANALYSIS(type) type##_analysis(),
  static const std::vector<AnalysisType> types = {GEARDYN_ANALYSIS_TYPES(GEARDYN_LIST_ANALYSIS)};
#undef GEARDYN_LIST_ANALYSIS
  return types;
}

const AnalysisType* find_analysis_type(std::string_view name) {
  for (const auto& t : registry())
    if (t.name == name) return &t;
  return nullptr;
}

const AnalysisType& type_of(const model::Analysis& analysis) {
  const AnalysisType* t = find_analysis_type(analysis.type);
  if (t == nullptr)
    throw std::logic_error("analysis '" + analysis.name + "' has the unregistered type '" +
                           analysis.type + "'");
  return *t;
}

}  // namespace geardyn::analyses
