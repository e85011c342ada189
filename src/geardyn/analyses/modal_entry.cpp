// The `type = "modal"` analysis in the registry: its model-file keys and their rules, its checks,
// how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/scalar_tables.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldType;
using model::FieldValue;
using model::Ref;
using model::TableContext;

std::vector<model::Field> keys() {
  return {
      reference_speed_key().to_settings(&ModalSettings::speed),
      n_modes_key().to_settings(&ModalSettings::n_modes),
      boolean("complex_modes", "Also compute the damped gyroscopic (complex) modes.")
          .def("true")
          .to_settings(&ModalSettings::complex_modes),
      method_key().to_settings_enum(&ModalSettings::method,
                                    {EigenMethod::Auto, EigenMethod::Dense, EigenMethod::Sparse}),
      number("shift_hz", kHertz, "Shift of the sparse solver: the modes nearest to it.")
          .def("0.0")
          .ge(0)
          .to_settings(&ModalSettings::shift),
  };
}

}  // namespace

AnalysisType modal_analysis() {
  AnalysisType type;
  type.name = "modal";
  type.declare = [] {
    auto d = declaration<ModalSettings>("modal",
                                        "Natural frequencies and mode shapes at one speed "
                                        "(undamped, and complex modes with damping and "
                                        "gyroscopic terms).");
    d.fields = keys();
    d.needs_rotor = true;
    return d;
  };
  type.run = [](const model::Model& m, const Analysis& a, const Context& c) {
    const auto& s = a.settings_of<ModalSettings>();
    ModalResult r = run_modal(c.system(), s, c.progress());
    AnalysisOutput out = modal_output(m, c.system(), r, a.name);
    return outcome(std::move(out), std::move(r));
  };
  type.scalars = {
      {"natural_frequency", "Hz", "Undamped natural frequency of mode `mode`.", {"mode"}}};
  type.scalar = scalar_from_tables;
  return type;
}

}  // namespace geardyn::analyses
