// The `type = "nonlinear_modes"` analysis in the registry: its model-file keys and their rules,
// its checks, how it runs.
#include <algorithm>
#include <limits>

#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/nonlinear_modes.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::TableContext;

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<NonlinearModesSettings>();
  if (!(s.amplitude_stop > s.amplitude_start))
    t.fail("amplitude_stop",
           fmt::format("an amplitude > amplitude_start = {}", value_text(s.amplitude_start)),
           value_text(s.amplitude_stop));
  if (s.time_samples > 0 && s.time_samples < 2 * s.harmonics + 1)
    t.fail("time_samples",
           fmt::format("at least 2 harmonics + 1 = {} samples per period", 2 * s.harmonics + 1),
           std::to_string(s.time_samples));
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& s = a.settings_of<NonlinearModesSettings>();
  const auto& m = check.model();
  check.check_named(path + ".sensors", s.sensors, model::names_of(m.sensors), "sensor", "sensors");
  if (m.nonlinear_elements.empty())
    check.fail(path + ".type", "a model with [[nonlinear_elements]]", "none",
               "use type = \"modal\" for the linear modes");
}

std::vector<model::Field> keys() {
  return {
      reference_speed_key().to_settings(&NonlinearModesSettings::speed),
      integer("mode",
              "The linear mode the nonlinear mode starts from (1: the lowest oscillatory mode of "
              "the structure with its elements linearised at rest).")
          .def("1")
          .ge(1)
          .to_settings(&NonlinearModesSettings::mode),
      number("amplitude_start", kNoUnit,
             "Modal amplitude a of the first point (a = sqrt(X1^H M X1) over the fundamental "
             "harmonics X1: for a mass-normalised linear mode the motion is a x the mode "
             "shape).")
          .unit_note("sqrt(kg) m")
          .def("1e-4")
          .gt(0)
          .to_settings(&NonlinearModesSettings::amplitude_start),
      number("amplitude_stop", kNoUnit, "Modal amplitude at which the curve ends.")
          .unit_note("sqrt(kg) m")
          .required()
          .gt(0)
          .to_settings(&NonlinearModesSettings::amplitude_stop),
      integer("harmonics", "Harmonics H balanced.")
          .def("7")
          .ge(1)
          .le(64)
          .to_settings(&NonlinearModesSettings::harmonics),
      integer("time_samples",
              "Time samples per period of the alternating frequency-time evaluation.")
          .ge(3)
          .le(65536)
          .note("(8 + 1) H + 1 rounded up to a power of two, at least 64")
          .to_settings(&NonlinearModesSettings::time_samples),
      integer("n_modes",
              "0: the model's DOFs (dense, up to 600); > 0: this many lowest modes at the "
              "reference speed.")
          .def("0")
          .ge(0)
          .to_settings(&NonlinearModesSettings::n_modes),
      sensors_key().to_settings(&NonlinearModesSettings::sensors),
      number("max_step", kNoUnit,
             "Largest continuation step in (scaled harmonics, log10 of the amplitude).")
          .def("0.1")
          .gt(0)
          .le(1)
          .to_settings(&NonlinearModesSettings::max_step),
      integer("max_points", "At most this many points.")
          .def("2000")
          .ge(2)
          .to_settings(&NonlinearModesSettings::max_points),
      number("tolerance", kNoUnit, "Newton tolerance, relative.")
          .def("1e-10")
          .gt(0)
          .lt(1e-2)
          .to_settings(&NonlinearModesSettings::tolerance),
  };
}

}  // namespace

AnalysisType nonlinear_modes_analysis() {
  AnalysisType type;
  type.name = "nonlinear_modes";
  type.declare = [] {
    auto d = declaration<NonlinearModesSettings>(
        "nonlinear_modes",
        "Nonlinear modes by the extended periodic motion concept: backbone curves (frequency, "
        "damping ratio and energy dissipated per cycle against amplitude) of the structure with "
        "its [[nonlinear_elements]], hardening springs and friction alike.");
    d.fields = keys();
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.run = runner(run_nonlinear_modes, nonlinear_modes_output);
  type.scalars = {
      {"linear_frequency", "Hz", "Frequency of the mode at rest (elements linearised).", {}},
      {"end_frequency", "Hz", "Frequency at the largest amplitude traced.", {}},
      {"max_damping_ratio",
       "",
       "Largest damping ratio along the backbone (a friction damper's best damping).",
       {}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) {
    const auto& r = result_of<NonlinearModesResult>(o);
    unit = q.quantity == "max_damping_ratio" ? "" : "Hz";
    if (q.quantity == "linear_frequency") return r.linear_frequency / units::kTwoPi;
    if (r.frequency.empty()) return std::numeric_limits<double>::quiet_NaN();
    if (q.quantity == "end_frequency") return r.frequency.back() / units::kTwoPi;
    return *std::max_element(r.damping_ratio.begin(), r.damping_ratio.end());
  };
  return type;
}

}  // namespace geardyn::analyses
