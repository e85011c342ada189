// The `type = "harmonic"` analysis in the registry: its model-file keys and their rules, its
// checks, how it runs and what it offers to sweeps.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
#include "geardyn/core/units.hpp"
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
      point_threads_key().to_settings(&HarmonicSettings::threads),
  };
}

constexpr double kHzPerRadS = 1.0 / units::kTwoPi;

int sensor_index(const FrfResult& r, const std::string& sensor) {
  for (std::size_t s = 0; s < r.sensors.size(); ++s)
    if (r.sensors[s].name == sensor) return static_cast<int>(s);
  throw std::runtime_error(fmt::format("no amplitude column for sensor '{}'", sensor));
}

// The sensor's amplitude curve as table "frf" lists it.
ResponseCurve response_curve(const FrfResult& r, int s) {
  ResponseCurve c;
  const Eigen::MatrixXcd response = r.response();
  c.groups.emplace_back();
  for (Eigen::Index i = 0; i < r.frequencies.size(); ++i) {
    c.x.push_back(r.frequencies[i] * kHzPerRadS);
    c.amplitude.push_back(std::abs(response(i, s)));
    c.groups.back().push_back(static_cast<std::size_t>(i));
  }
  c.x_unit = "Hz";
  c.amplitude_unit = r.amplitude_unit(s);
  c.per_rad_s = 1.0 / units::kTwoPi;
  return c;
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const FrfResult& r = result_of<FrfResult>(o);
  const int s = sensor_index(r, q.sensor);
  if (q.quantity == "peak_damping_ratio") {
    // As the peak table reports it: only for a resolved band.
    const FrfPeak* highest = nullptr;
    for (const auto& p : r.peaks)
      if (p.sensor == s && (highest == nullptr || p.amplitude > highest->amplitude)) highest = &p;
    unit.clear();
    if (highest == nullptr || !highest->resolved || !(highest->q_factor > 0.0))
      return std::numeric_limits<double>::quiet_NaN();
    return highest->damping_ratio();
  }
  return response_scalar(response_curve(r, s), q, unit);
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
  type.run = runner(run_harmonic, harmonic_output);
  type.scalars = {
      {"peak_amplitude", "", "Largest response amplitude at `sensor`.", {"sensor"}},
      {"peak_location", "Hz", "Frequency of that peak.", {"sensor"}},
      {"amplitude_at", "", "Amplitude at `sensor` at frequency `at_hz`.", {"sensor", "at_hz"}},
      {"peak_damping_ratio",
       "",
       "Damping ratio 1/(2Q) from the half-power band of the highest resonance peak at "
       "`sensor` (NaN when its band is not resolved).",
       {"sensor"}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
