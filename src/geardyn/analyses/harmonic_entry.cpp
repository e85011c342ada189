// The `type = "harmonic"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/harmonic.hpp"
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

void finish(Analysis& a, const TableContext& t) {
  auto& h = a.settings_of<HarmonicSettings>();
  if (h.f_max <= h.f_min)
    t.fail("frequency_stop_hz",
           fmt::format("a frequency > frequency_start_hz = {} Hz (the range would be empty)",
                       value_text(h.f_min / kHertz.to_si)),
           fmt::format("{} Hz", value_text(h.f_max / kHertz.to_si)));
  if (h.spacing == Spacing::Log && h.f_min <= 0.0)
    t.fail("frequency_start_hz", "a frequency > 0 Hz for spacing = \"log\"", "0 Hz");
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& h = a.settings_of<HarmonicSettings>();
  const auto& m = check.model();
  if (!h.input_node.empty()) check.check_node(path + ".input_node", h.input_node);
  check.check_named(path + ".forces", h.forces, model::names_of(m.forces), "force", "forces");
  check.check_named(path + ".sensors", h.sensors, model::names_of(m.sensors), "sensor", "sensors");
}

std::vector<model::Field> keys() {
  return {
      reference_speed_key().to_settings(&HarmonicSettings::speed),
      number("frequency_start_hz", kHertz, "First frequency.")
          .required()
          .ge(0)
          .to_settings(&HarmonicSettings::f_min),
      number("frequency_stop_hz", kHertz, "Last frequency (> frequency_start_hz).")
          .required()
          .gt(0)
          .to_settings(&HarmonicSettings::f_max),
      integer("frequency_count", "Number of frequencies (before adaptive refinement).")
          .def("200")
          .ge(2)
          .le(1000000)
          .to_settings(&HarmonicSettings::n_points),
      spacing_key().to_settings_enum(&HarmonicSettings::spacing, {Spacing::Linear, Spacing::Log}),
      boolean("adaptive", "Refine the frequency grid around peaks.")
          .def("true")
          .to_settings(&HarmonicSettings::adaptive),
      reference("input_node", Ref::Node, "Node of the unit-force input of an FRF.")
          .required()
          .to_settings(&HarmonicSettings::input_node),
      choice("input_dof", kComponentChoices, "DOF of the unit-force input.")
          .def("\"ux\"")
          .to_settings(&HarmonicSettings::input_dof),
      names("forces", Ref::Force, "Named [[forces]] applied together (forced response).")
          .min_items(1)
          .to_settings(&HarmonicSettings::forces),
      choice("quantity", {"receptance", "mobility", "accelerance"},
             "Response quantity: displacement, velocity or acceleration per force.")
          .def("\"receptance\"")
          .to_settings_enum(&HarmonicSettings::quantity,
                            {ResponseQuantity::Receptance, ResponseQuantity::Mobility,
                             ResponseQuantity::Accelerance}),
      sensors_key().to_settings(&HarmonicSettings::sensors),
  };
}

}  // namespace

AnalysisType harmonic_analysis() {
  AnalysisType type;
  type.name = "harmonic";
  type.declare = [] {
    auto d = declaration<HarmonicSettings>("harmonic",
                                           "Frequency response at one speed: an FRF from a unit "
                                           "force, or the response to named forces.");
    d.fields = keys();
    d.choices = {{{{"input_node", "input_dof"}, {"forces"}}, true, {}}};
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.run = [](const model::Model& m, const Analysis& a, const Context& c) {
    const auto& s = a.settings_of<HarmonicSettings>();
    FrfResult r = run_harmonic(m, c.system(), s, c.progress());
    AnalysisOutput out = harmonic_output(m, c.system(), r, a.name);
    return outcome(std::move(out), std::move(r));
  };
  type.scalars = {
      {"peak_amplitude", "", "Largest response amplitude at `sensor`.", {"sensor"}},
      {"peak_location", "Hz", "Frequency of that peak.", {"sensor"}},
      {"amplitude_at", "", "Amplitude at `sensor` at frequency `at_hz`.", {"sensor", "at_hz"}}};
  type.scalar = scalar_from_tables;
  return type;
}

}  // namespace geardyn::analyses
