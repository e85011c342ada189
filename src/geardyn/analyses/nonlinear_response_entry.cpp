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

// The speed range of parameter = "speed" (and no speed keys otherwise).
void finish_speed(const NonlinearResponseSettings& s, const TableContext& t) {
  const bool by_speed = s.parameter == ContinuationParameter::Speed;
  for (const char* key : {"speed_start_rpm", "speed_stop_rpm"}) {
    if (by_speed && !t.has(key))
      t.fail(key, "the speed range of the continuation (parameter = \"speed\")", "none");
    if (!by_speed && t.has(key))
      t.fail(key, "no speed range unless parameter = \"speed\"", "one",
             "give parameter = \"speed\" to trace the response over the speed");
  }
  if (!by_speed && t.has("order"))
    t.fail("order", "no order unless parameter = \"speed\"", "one",
           "the order ties the fundamental to the speed of a speed continuation");
  if (!by_speed) return;
  for (const char* key : {"frequency_hz", "frequency_start_hz", "frequency_stop_hz"})
    if (t.has(key))
      t.fail(key, "no frequency with parameter = \"speed\" (the fundamental is order x speed)",
             "one");
  if (!(s.speed_stop > s.speed_start))
    t.fail(
        "speed_stop_rpm",
        fmt::format("a speed > speed_start_rpm = {} rpm", value_text(s.speed_start / kRpm.to_si)),
        fmt::format("{} rpm", value_text(s.speed_stop / kRpm.to_si)));
}

// base_motion with exactly one of its amplitudes.
void finish_base_motion(const NonlinearResponseSettings& s, const TableContext& t) {
  const bool a = t.has("base_acceleration"), d = t.has("base_displacement");
  if (s.base_motion == BaseMotion::None) {
    for (const char* key : {"base_acceleration", "base_displacement"})
      if (t.has(key)) t.fail(key, "an amplitude together with base_motion", "no base_motion");
    return;
  }
  if (a == d)
    t.fail(a ? "base_displacement" : "base_motion",
           "one amplitude of the base motion: base_acceleration or base_displacement",
           a ? "both" : "none");
}

// The `coordinates` key against n_modes (absent: physical for n_modes = 0, modal otherwise).
void finish_form(NonlinearResponseSettings& s, const TableContext& t) {
  if (!t.has("coordinates"))
    s.form = s.n_modes > 0 ? NonlinearForm::Modal : NonlinearForm::Physical;
  if (s.form == NonlinearForm::Physical && s.n_modes > 0)
    t.fail("n_modes", "0 with coordinates = \"physical\"", std::to_string(s.n_modes));
  if (s.form != NonlinearForm::Physical && s.n_modes < 1)
    t.fail("n_modes",
           fmt::format("at least 1 mode with coordinates = \"{}\"",
                       s.form == NonlinearForm::Modal ? "modal" : "condensed"),
           std::to_string(s.n_modes));
  if (s.form != NonlinearForm::Condensed) return;
  if (s.parameter == ContinuationParameter::Speed)
    t.fail("parameter", "\"frequency\" or \"force_level\" with coordinates = \"condensed\"",
           "\"speed\"",
           "the receptance is built once at the reference speed: use coordinates = \"modal\" "
           "or \"physical\" to trace the speed");
  if (s.parameter == ContinuationParameter::Frequency && t.has("base_displacement"))
    t.fail("base_displacement",
           "base_acceleration with coordinates = \"condensed\" and parameter = \"frequency\"",
           "base_displacement",
           "its force grows with the frequency squared; the condensed excitation is fixed");
}

void finish(Analysis& a, const TableContext& t) {
  auto& s = a.settings_of<NonlinearResponseSettings>();
  finish_speed(s, t);
  finish_base_motion(s, t);
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
  } else if (s.parameter == ContinuationParameter::ForceLevel) {
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
  finish_form(s, t);
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
  check.check_named(path + ".unbalances", s.unbalances, model::names_of(m.unbalances), "unbalance",
                    "unbalances");
  const bool mesh =
      std::any_of(m.nonlinear_elements.begin(), m.nonlinear_elements.end(),
                  [](const auto& e) { return e.kind == model::NonlinearElementKind::GearMesh; });
  if (s.forces.empty() && !mesh && s.unbalances.empty() && s.base_motion == BaseMotion::None)
    check.fail(path + ".forces",
               "the forces that excite the structure (or unbalances, a base_motion, or a "
               "gear_mesh element whose unloaded TE does)",
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
          .note("the excitation is the unbalances, the base motion or the unloaded TE of gear_mesh "
                "elements")
          .min_items(1)
          .to_settings(&NonlinearResponseSettings::forces),
      names("mean_forces", Ref::Force,
            "Named [[forces]] applied as constant loads of value amplitude x cos(phase) (a mean "
            "torque that keeps a gear mesh in contact, a static preload).")
          .to_settings(&NonlinearResponseSettings::mean_forces),
      choice(
          "parameter", {"frequency", "force_level", "speed"},
          "What the continuation varies: the fundamental over [frequency_start_hz, "
          "frequency_stop_hz], the factor on the excitation (`forces`, `mean_forces`, "
          "`unbalances` and `base_motion` alike) from force_factor_start to force_factor_stop at "
          "frequency_hz, or the speed over [speed_start_rpm, speed_stop_rpm] with the fundamental "
          "order x speed, the speed-dependent bearings, the gyroscopic terms and the unbalance "
          "force m e W^2 at each speed.")
          .def("\"frequency\"")
          .to_settings_enum(&NonlinearResponseSettings::parameter,
                            {ContinuationParameter::Frequency, ContinuationParameter::ForceLevel,
                             ContinuationParameter::Speed}),
      number("speed_start_rpm", kRpm, "First speed (parameter = speed).")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::speed_start),
      number("speed_stop_rpm", kRpm, "Last speed (parameter = speed; > speed_start_rpm).")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::speed_stop),
      number("order", kNoUnit,
             "Fundamental of a speed continuation as a multiple of the speed: w = order x W "
             "(an unbalance on a node of speed ratio rho acts on harmonic rho / order; a "
             "gear_mesh element's fundamental is its mesh order, teeth x speed ratio).")
          .def("1.0")
          .gt(0)
          .to_settings(&NonlinearResponseSettings::order),
      names("unbalances", Ref::Unbalance,
            "Named [[unbalances]]: the rotating force m e (rho W)^2 of the `unbalance` analysis. "
            "With parameter = speed it follows the speed (harmonic rho / order); otherwise it "
            "acts at the fundamental with its amplitude at the reference speed speed_rpm.")
          .to_settings(&NonlinearResponseSettings::unbalances),
      choice("base_motion", {"x", "y", "z", "rx", "ry", "rz"},
             "Harmonic motion of the ground along a global axis or about it (through the "
             "centroid of the nodes), a_g = Re(A e^{i w t}): the effective force -M r a_g in "
             "coordinates relative to the ground (r the rigid-body motion of the direction); "
             "the sensors read the motion relative to the ground.")
          .to_settings_enum(&NonlinearResponseSettings::base_motion,
                            {BaseMotion::X, BaseMotion::Y, BaseMotion::Z, BaseMotion::Rx,
                             BaseMotion::Ry, BaseMotion::Rz}),
      number("base_acceleration", kNoUnit,
             "Acceleration amplitude A of the base motion [m/s^2; rad/s^2 for a rotation].")
          .to_settings(&NonlinearResponseSettings::base_acceleration),
      number("base_displacement", kNoUnit,
             "Displacement amplitude D of the base motion [m; rad for a rotation]: A = -w^2 D "
             "at the fundamental w.")
          .to_settings(&NonlinearResponseSettings::base_displacement),
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
              "the highest frequency), or with coordinates = \"condensed\" the modes kept in "
              "the receptance.")
          .def("0")
          .ge(0)
          .to_settings(&NonlinearResponseSettings::n_modes),
      choice("coordinates", {"physical", "modal", "condensed"},
             "Coordinates of the balance: \"physical\" the model's DOFs (n_modes = 0); "
             "\"modal\" its n_modes lowest modes (drops the static contribution of the higher "
             "modes); \"condensed\" the nonlinear elements' relative coordinates only, through "
             "the receptance of the n_modes lowest modes plus the residual flexibility of the "
             "others (exact for the static part; any model size, unknowns: the elements' "
             "coordinates x (2H + 1); modal damping from the diagonal of the modal damping "
             "matrix; not with gyroscopic terms at speed, a loss factor, cross-coupled "
             "bearings, parameter = \"speed\" or stability = \"monodromy\").")
          .note("\"physical\" when n_modes = 0, \"modal\" otherwise")
          .to_settings_enum(
              &NonlinearResponseSettings::form,
              {NonlinearForm::Physical, NonlinearForm::Modal, NonlinearForm::Condensed}),
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
  double best = -1.0, at = std::numeric_limits<double>::quiet_NaN(), at_speed = at;
  for (std::size_t i = 0; i < r.sensor_coefficients.size(); ++i) {
    const Eigen::VectorXd c = r.sensor_coefficients[i].row(s).transpose();
    const double v = q.quantity == "peak_rms" ? series_rms(c) : harmonic_amplitude(c, 1);
    if (v > best) {
      best = v;
      at = r.frequency[i];
      at_speed = r.speed[i];
    }
  }
  if (q.quantity == "peak_location") {
    unit = "Hz";
    return at / units::kTwoPi;
  }
  if (q.quantity == "peak_speed") {
    unit = "rpm";
    return at_speed * 60.0 / units::kTwoPi;
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
        "forcing by named forces, unbalances, base motion or a gear mesh's TE; continuation over "
        "frequency, force level or speed through turning points, amplitude per "
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
                   {"sensor"}},
                  {"peak_speed",
                   "rpm",
                   "Speed of the largest first-harmonic amplitude (the reference speed unless "
                   "parameter = \"speed\").",
                   {"sensor"}}};
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
