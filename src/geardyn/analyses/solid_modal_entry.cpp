// The `type = "solid_modal"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/solid_modal.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  (void)check_solid_use(path, a.settings_of<SolidModalSettings>().solid, check, false);
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<SolidModalResult>(o);
  if (q.quantity != "natural_frequency")
    throw std::runtime_error(fmt::format("solid_modal offers no scalar \'{}\'", q.quantity));
  unit = std::string("Hz");
  if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.frequency_hz.size())
    throw std::runtime_error(
        fmt::format("natural_frequency: mode {} of {} computed", q.mode, r.frequency_hz.size()));
  return r.frequency_hz[static_cast<std::size_t>(q.mode - 1)];
}

std::vector<model::Field> keys() {
  return {
      n_modes_key().to_settings(&SolidModalSettings::n_modes),
      solid_key().to_settings(&SolidModalSettings::solid),
      number("f_max_hz", kHertz, "Every mode up to this frequency (n_modes is ignored).")
          .gt(0)
          .note("n_modes modes")
          .to_settings(&SolidModalSettings::f_max),
      boolean("full_wheel", "Cyclic solid: replicate the sector to the whole wheel first.")
          .def("false")
          .to_settings(&SolidModalSettings::full_wheel),
      shapes_key().to_settings(&SolidModalSettings::shapes),
  };
}

}  // namespace

AnalysisType solid_modal_analysis() {
  AnalysisType type;
  type.name = "solid_modal";
  type.declare = [] {
    auto d = declaration<SolidModalSettings>("solid_modal",
                                             "Natural frequencies and mode shapes of a solid "
                                             "component (sparse shift-invert Lanczos).");
    d.fields = keys();
    d.check = check;
    return d;
  };
  type.run = runner(run_solid_modal, solid_modal_output);
  type.scalars = {{"natural_frequency",
                   "Hz",
                   "Natural frequency of mode `mode` of the solid (the mesh as given, or the "
                   "whole wheel with full_wheel), in ascending order.",
                   {"mode"}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
