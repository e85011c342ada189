// The `type = "nonlinear_response"` analysis in the registry: its model-file keys and their rules,
// its checks, how it runs and what it offers to sweeps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::Ref;
using model::TableContext;

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<NonlinearResponseSettings>();
  if (s.parameter == ContinuationParameter::Frequency) {
    for (const char* key : {"frequency_start_hz", "frequency_stop_hz"})
      if (!t.has(key))
        t.fail(key, "the range of the fundamental (parameter = \"frequency\")", "none");
    if (t.has("frequency_hz"))
      t.fail("frequency_hz", "no fixed frequency with parameter = \"frequency\"", "one",
             "give parameter = \"force_level\" to vary the force at this frequency");
    if (!(s.f_stop > s.f_start))
      t.fail("frequency_stop_hz",
             fmt::format("a frequency > frequency_start_hz = {} Hz",
                         value_text(s.f_start / kHertz.to_si)),
             fmt::format("{} Hz", value_text(s.f_stop / kHertz.to_si)));
  } else {
    if (!t.has("frequency_hz"))
      t.fail("frequency_hz", "the fixed fundamental of a force-level continuation", "none");
    for (const char* key : {"frequency_start_hz", "frequency_stop_hz"})
      if (t.has(key)) t.fail(key, "no frequency range with parameter = \"force_level\"", "one");
    if (s.level_stop == s.level_start)
      t.fail("force_factor_stop", "a factor other than force_factor_start",
             value_text(s.level_stop));
  }
  if (s.time_samples > 0 && s.time_samples < 2 * s.harmonics + 1)
    t.fail("time_samples",
           fmt::format("at least 2 harmonics + 1 = {} samples per period", 2 * s.harmonics + 1),
           std::to_string(s.time_samples));
  if (s.max_step < s.step)
    t.fail("max_step", fmt::format("a step >= step = {}", value_text(s.step)),
           value_text(s.max_step));
}

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& s = a.settings_of<NonlinearResponseSettings>();
  const auto& m = check.model();
  check.check_named(path + ".forces", s.forces, model::names_of(m.forces), "force", "forces");
  check.check_named(path + ".mean_forces", s.mean_forces, model::names_of(m.forces), "force",
                    "forces");
  check.check_named(path + ".sensors", s.sensors, model::names_of(m.sensors), "sensor", "sensors");
  const bool mesh =
      std::any_of(m.nonlinear_elements.begin(), m.nonlinear_elements.end(),
                  [](const auto& e) { return e.kind == model::NonlinearElementKind::GearMesh; });
  if (s.forces.empty() && !mesh)
    check.fail(path + ".forces",
               "the forces that excite the structure (or a gear_mesh element "
               "whose unloaded TE does)",
               "none");
  if (m.nonlinear_elements.empty())
    check.fail(path + ".type",
               "a model with [[nonlinear_elements]] (what the harmonic balance is for)", "none",
               "use type = \"harmonic\" for the linear response");
}

std::vector<model::Field> keys() {
  return {
      reference_speed_key().to_settings(&NonlinearResponseSettings::speed),
      names("forces", Ref::Force,
            "Named [[forces]] acting at the fundamental (amplitude and phase: f = Re(A e^{i "
            "phi} e^{i w t})).")
          .note("the excitation is the unloaded TE of gear_mesh elements")
          .min_items(1)
          .to_settings(&NonlinearResponseSettings::forces),
      names("mean_forces", Ref::Force,
            "Named [[forces]] applied as constant loads of value amplitude x cos(phase) (a mean "
            "torque that keeps a gear mesh in contact, a static preload).")
          .to_settings(&NonlinearResponseSettings::mean_forces),
      choice(
          "parameter", {"frequency", "force_level"},
          "What the continuation varies: the fundamental over [frequency_start_hz, "
          "frequency_stop_hz], or the factor on the excitation (`forces` and `mean_forces` alike) "
          "from force_factor_start to "
          "force_factor_stop at frequency_hz.")
          .def("\"frequency\"")
          .to_settings_enum(&NonlinearResponseSettings::parameter,
                            {ContinuationParameter::Frequency, ContinuationParameter::ForceLevel}),
      number("frequency_start_hz", kHertz, "First fundamental frequency (parameter = frequency).")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::f_start),
      number("frequency_stop_hz", kHertz, "Last fundamental frequency (parameter = frequency).")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::f_stop),
      number("frequency_hz", kHertz, "Fixed fundamental of a force-level continuation.")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::frequency),
      number("force_factor_start", kNoUnit, "First factor on the excitation (force_level).")
          .def("0.0")
          .to_settings(&NonlinearResponseSettings::level_start),
      number("force_factor_stop", kNoUnit, "Last factor on the excitation (force_level).")
          .def("1.0")
          .to_settings(&NonlinearResponseSettings::level_stop),
      integer("harmonics",
              "Harmonics H balanced (1: the fundamental only; contacts and friction need more "
              "to resolve their force's shape: 5 to 15).")
          .def("7")
          .ge(0)
          .le(64)
          .to_settings(&NonlinearResponseSettings::harmonics),
      integer("time_samples",
              "Time samples per period of the alternating frequency-time evaluation.")
          .ge(1)
          .le(65536)
          .note("(8 + 1) H + 1 rounded up to a power of two, at least 64")
          .to_settings(&NonlinearResponseSettings::time_samples),
      integer("n_modes",
              "0: solve on the model's DOFs (exact, dense: up to 600 DOFs); > 0: on this many "
              "lowest modes at the reference speed (larger models; keep modes well above H x "
              "the highest frequency).")
          .def("0")
          .ge(0)
          .to_settings(&NonlinearResponseSettings::n_modes),
      sensors_key().to_settings(&NonlinearResponseSettings::sensors),
      number("step", kNoUnit,
             "First continuation step, in the arc length scaled by the range and the linear "
             "response amplitude.")
          .def("0.01")
          .gt(0)
          .le(0.5)
          .to_settings(&NonlinearResponseSettings::step),
      number("max_step", kNoUnit, "Largest continuation step (same scale as step).")
          .def("0.05")
          .gt(0)
          .le(1)
          .to_settings(&NonlinearResponseSettings::max_step),
      integer("max_points", "At most this many continuation points.")
          .def("5000")
          .ge(2)
          .to_settings(&NonlinearResponseSettings::max_points),
      number("tolerance", kNoUnit,
             "Newton tolerance: ||R|| <= tolerance x (the larger of the force amplitude and "
             "the stiffness force).")
          .def("1e-9")
          .gt(0)
          .lt(1e-2)
          .to_settings(&NonlinearResponseSettings::tolerance),
      choice("stability", {"fold", "hill", "monodromy"},
             "Stability of each point: \"fold\" from the turning points of the curve (valid "
             "for friction, blind to period doubling and quasi-periodic loss); \"hill\": Hill's "
             "method on the balance's Jacobian (every kind; approximate for hysteretic "
             "elements); \"monodromy\": Floquet multipliers of a time march over one period "
             "through the elements' laws (every kind, valid for stick-slip; the costliest).")
          .def("\"fold\"")
          .to_settings_enum(
              &NonlinearResponseSettings::stability,
              {NonlinearStability::Fold, NonlinearStability::Hill, NonlinearStability::Monodromy}),
  };
}

int sensor_index(const NonlinearResponseResult& r, const std::string& sensor) {
  for (std::size_t s = 0; s < r.sensors.size(); ++s)
    if (r.sensors[s] == sensor) return static_cast<int>(s);
  throw std::runtime_error(fmt::format("no response of sensor '{}'", sensor));
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const auto& r = result_of<NonlinearResponseResult>(o);
  const int s = sensor_index(r, q.sensor);
  unit = r.sensor_rotational[static_cast<std::size_t>(s)] ? "rad" : "m";
  double best = -1.0, at = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < r.sensor_coefficients.size(); ++i) {
    const Eigen::VectorXd c = r.sensor_coefficients[i].row(s).transpose();
    const double v = q.quantity == "peak_rms" ? series_rms(c) : harmonic_amplitude(c, 1);
    if (v > best) {
      best = v;
      at = r.frequency[i];
    }
  }
  if (q.quantity == "peak_location") {
    unit = "Hz";
    return at / units::kTwoPi;
  }
  return best;
}

}  // namespace

AnalysisType nonlinear_response_analysis() {
  AnalysisType type;
  type.name = "nonlinear_response";
  type.declare = [] {
    auto d = declaration<NonlinearResponseSettings>(
        "nonlinear_response",
        "Nonlinear forced response by harmonic balance with the [[nonlinear_elements]]: "
        "continuation over frequency or force level through turning points, amplitude per "
        "harmonic and RMS per sensor, stability, energy dissipated per element and hysteresis "
        "loops.");
    d.fields = keys();
    d.finish = finish;
    d.check = check;
    d.needs_rotor = true;
    return d;
  };
  type.run = runner(run_nonlinear_response, nonlinear_response_output);
  type.scalars = {{"peak_amplitude",
                   "",
                   "Largest first-harmonic amplitude at `sensor` over the curve.",
                   {"sensor"}},
                  {"peak_rms",
                   "",
                   "Largest RMS of the periodic response at `sensor` over the curve.",
                   {"sensor"}},
                  {"peak_location",
                   "Hz",
                   "Fundamental frequency of the largest first-harmonic amplitude.",
                   {"sensor"}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
