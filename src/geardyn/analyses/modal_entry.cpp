// The `type = "modal"` analysis in the registry: its model-file keys and their rules, its checks,
// how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
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
  type.run = runner(run_modal, modal_output);
  type.scalars = {
      {"natural_frequency", "Hz", "Undamped natural frequency of mode `mode`.", {"mode"}},
      {"damping_ratio",
       "",
       "Damping ratio -Re(lambda) / |lambda| of mode `mode` (0 for undamped modes).",
       {"mode"}},
      {"log_decrement",
       "",
       "Logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2) of mode `mode` (NaN when "
       "overdamped).",
       {"mode"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) {
    // The modes the "modes" table lists: complex when computed, else undamped.
    const Mode& mode = nth_mode(result_of<ModalResult>(o).primary(), q.mode);
    if (q.quantity == "natural_frequency") {
      unit = "Hz";
      return mode.frequency_hz;
    }
    unit.clear();
    if (q.quantity == "damping_ratio") return mode.damping_ratio;
    if (q.quantity == "log_decrement") return log_decrement(mode.damping_ratio);
    unknown_scalar("modal", q.quantity);
  };
  return type;
}

}  // namespace geardyn::analyses
