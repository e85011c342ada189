#include "geardyn/analyses/transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/plot_envelope.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/signal/spectrum.hpp"
#include "geardyn/transient/linear_rotor_system.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRadPerSToRpm = 60.0 / units::kTwoPi;
constexpr int kMinSpectrumSamples = 16;
constexpr std::size_t kMaxPlotPoints = 4000;

std::string unit_suffix(bool rotational) { return rotational ? "rad" : "m"; }

bool is_rotation(model::Component c) {
  return c == model::Component::Rx || c == model::Component::Ry || c == model::Component::Rz;
}

}  // namespace

TransientCost estimate_cost(const TransientSettings& s, int n_sensors) {
  TransientCost c;
  // ceil, forgiving the rounding of duration / time_step (0.3 / 1e-4 = 2999.9999999999995).
  c.steps = std::max(1.0, std::ceil(s.duration / s.time_step * (1.0 - 1e-9)));
  c.samples = std::floor(c.steps / std::max(1, s.output_every)) + 1.0;
  c.columns = 2 + n_sensors;
  c.csv_bytes = c.samples * c.columns * TransientCost::kBytesPerValue;
  c.memory_bytes = 2.0 * c.samples * c.columns * 8.0;
  return c;
}

namespace {

std::string bytes_text(double b) {
  return b >= 1e9   ? fmt::format("{:.3g} GB", b / 1e9)
         : b >= 1e6 ? fmt::format("{:.3g} MB", b / 1e6)
                    : fmt::format("{:.3g} kB", b / 1e3);
}

}  // namespace

std::string TransientCost::describe() const {
  return fmt::format(
      "{:.4g} steps, {:.4g} stored samples x {} columns: time_history.csv about {}, {} in "
      "memory",
      steps, samples, columns, bytes_text(csv_bytes), bytes_text(memory_bytes));
}

std::string TransientCost::excess() const {
  if (steps > kMaxSteps)
    return fmt::format("at most {:.0e} time steps (duration / time_step)", kMaxSteps);
  if (csv_bytes > kMaxOutputBytes)
    return fmt::format("a time history of at most {} (samples x columns x {:g} bytes)",
                       bytes_text(kMaxOutputBytes), kBytesPerValue);
  return "";
}

namespace {

// "duration = 10 s, time_step = 1e-07 s, output_every = 1: 1e+08 steps, ...".
std::string cost_found(const TransientSettings& s, const TransientCost& cost) {
  return fmt::format("duration = {:g} s, time_step = {:g} s, output_every = {}: {}", s.duration,
                     s.time_step, s.output_every, cost.describe());
}

void validate(const model::Model& model, const TransientSettings& s, const Context& context) {
  auto fail = [&](const std::string& key, const std::string& expected, const std::string& found) {
    throw context.error(key, expected, found);
  };
  if (!(s.duration > 0.0) || !std::isfinite(s.duration))
    fail("duration", "a positive duration [s]", fmt::format("{}", s.duration));
  if (!(s.time_step > 0.0) || !std::isfinite(s.time_step))
    fail("time_step", "a positive time step [s]", fmt::format("{}", s.time_step));
  if (s.time_step > s.duration)
    fail("time_step", fmt::format("a time step no longer than the duration ({} s)", s.duration),
         fmt::format("{}", s.time_step));
  if (!(s.speed >= 0.0) || !std::isfinite(s.speed))
    fail("speed_rpm", "a speed >= 0 [rpm]", fmt::format("{}", s.speed * kRadPerSToRpm));
  if (!std::isnan(s.speed_end) && (!(s.speed_end >= 0.0) || !std::isfinite(s.speed_end)))
    fail("speed_end_rpm", "a speed >= 0 [rpm]", fmt::format("{}", s.speed_end * kRadPerSToRpm));
  if (!(s.rho_infinity >= 0.0 && s.rho_infinity <= 1.0))
    fail("rho_infinity", "a value in [0, 1]", fmt::format("{}", s.rho_infinity));
  if (!(s.steady_fraction > 0.0 && s.steady_fraction <= 1.0))
    fail("steady_fraction", "a fraction in (0, 1]", fmt::format("{}", s.steady_fraction));
  if (s.output_every < 1)
    fail("output_every", "an integer >= 1", fmt::format("{}", s.output_every));
  const double steps = std::ceil(s.duration / s.time_step * (1.0 - 1e-9));
  if (s.output_every > steps)
    fail("output_every",
         fmt::format("at most the number of steps ({:.0f}) so that samples after t = 0 are stored",
                     steps),
         fmt::format("{}", s.output_every));
  const int n_sensors =
      static_cast<int>(s.sensors.empty() ? model.sensors.size() : s.sensors.size());
  if (const TransientCost cost = estimate_cost(s, n_sensors); !cost.excess().empty())
    throw context.error(cost.steps > TransientCost::kMaxSteps ? "time_step" : "output_every",
                        cost.excess(), cost_found(s, cost),
                        "raise time_step or output_every, or shorten duration");
  for (const auto& name : s.unbalances)
    if (std::none_of(model.unbalances.begin(), model.unbalances.end(),
                     [&](const model::Unbalance& u) { return u.name == name; }))
      fail("unbalances", "names of unbalances of the model", "'" + name + "'");
  for (const auto& name : s.sensors)
    if (std::none_of(model.sensors.begin(), model.sensors.end(),
                     [&](const model::Sensor& x) { return x.name == name; }))
      fail("sensors", "names of sensors of the model", "'" + name + "'");
}

// Largest and smallest distance from the centre, and the sense of travel. The centre is the
// middle of the bounding box: exact for an ellipse whatever part of a period the record ends
// on, where the mean of a record of N + fraction periods is off by up to major / (2 pi N).
TransientOrbit estimate_orbit(const Eigen::Ref<const Eigen::VectorXd>& x,
                              const Eigen::Ref<const Eigen::VectorXd>& y) {
  TransientOrbit o;
  const double cx = 0.5 * (x.maxCoeff() + x.minCoeff());
  const double cy = 0.5 * (y.maxCoeff() + y.minCoeff());
  const Eigen::Index n = x.size();
  double major = 0.0, minor = std::numeric_limits<double>::infinity();
  double swept = 0.0, scale = 0.0;  // sum of cross products, sum of |p||dp|
  for (Eigen::Index k = 0; k < n; ++k) {
    const double px = x[k] - cx, py = y[k] - cy;
    const double r = std::hypot(px, py);
    major = std::max(major, r);
    minor = std::min(minor, r);
    if (k + 1 < n) {
      const double dx = x[k + 1] - x[k], dy = y[k + 1] - y[k];
      swept += px * dy - py * dx;
      scale += r * std::hypot(dx, dy);
    }
  }
  o.major = major;
  o.minor = minor;
  if (scale > 0.0 && std::abs(swept) > 1e-6 * scale)
    o.whirl = swept > 0.0 ? signal::Whirl::Forward : signal::Whirl::Backward;
  return o;
}

}  // namespace

namespace {

// The selected sensors, in model order (sets the sensor fields of `result`).
std::vector<const model::Sensor*> select_transient_sensors(const model::Model& model,
                                                           const fe::LinearSystem& system,
                                                           const TransientSettings& settings,
                                                           TransientResult& result) {
  std::vector<const model::Sensor*> selected;
  for (const auto& sensor : model.sensors) {
    if (!settings.sensors.empty() && std::find(settings.sensors.begin(), settings.sensors.end(),
                                               sensor.name) == settings.sensors.end())
      continue;
    const int node = system.dofs.find_node(sensor.node);
    if (node < 0)
      throw InputError(sensor.where, "sensors." + sensor.name + ".node", "a node of the model",
                       "'" + sensor.node + "'");
    selected.push_back(&sensor);
    result.sensor_names.push_back(sensor.name);
    result.sensor_rotational.push_back(is_rotation(sensor.dof));
    result.sensor_equations.push_back(system.dofs.dof(node, sensor.dof));
  }
  return selected;
}

// Integrates from rest and stores every output_every-th sample of the sensors.
void integrate_record(const model::Model& model, const fe::LinearSystem& system,
                      const TransientSettings& settings, Progress& progress,
                      TransientResult& result) {
  const transient::SpeedProfile profile =
      std::isnan(settings.speed_end)
          ? transient::SpeedProfile::constant(settings.speed)
          : transient::SpeedProfile::run_up(settings.speed, settings.speed_end, settings.duration);
  transient::LinearRotorSystem rotor(model, system, profile, settings.unbalances);

  transient::IntegratorOptions options;
  options.scheme = settings.integrator == Integrator::Newmark ? transient::Scheme::Newmark
                                                              : transient::Scheme::GeneralizedAlpha;
  options.rho_infinity = settings.rho_infinity;
  options.time_step = settings.time_step;
  options.num_steps = result.steps;

  const std::size_t n_sensors = result.sensor_names.size();
  const std::size_t capacity = static_cast<std::size_t>(result.steps / settings.output_every) + 2;
  result.time.reserve(capacity);
  result.speed.reserve(capacity);
  std::vector<double> samples;  // row-major samples x sensors while recording
  samples.reserve(capacity * n_sensors);

  const int n = system.size();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  result.integration = transient::integrate(
      rotor, options, q, v,
      [&](int step, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
          const Eigen::VectorXd&) {
        if (step % settings.output_every != 0) return;
        result.time.push_back(t);
        result.speed.push_back(profile.speed(t));
        for (std::size_t s = 0; s < n_sensors; ++s) {
          const int e = result.sensor_equations[s];
          samples.push_back(e >= 0 ? qs[e] : 0.0);
        }
      },
      progress);

  const Eigen::Index rows = static_cast<Eigen::Index>(result.time.size());
  result.values =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          samples.data(), rows, static_cast<Eigen::Index>(n_sensors));
}

// Hann amplitude spectra of the steady part of every sensor.
void steady_spectra(TransientResult& result, Eigen::Index steady_rows) {
  const std::size_t n_sensors = result.sensor_names.size();
  if (steady_rows < kMinSpectrumSamples || n_sensors == 0) return;
  const double fs = 1.0 / result.sample_interval;
  for (std::size_t s = 0; s < n_sensors; ++s) {
    const Eigen::VectorXd x = result.values.col(static_cast<Eigen::Index>(s)).tail(steady_rows);
    const auto spectrum = signal::amplitude_spectrum(x, fs, signal::Window::Hann);
    if (s == 0) {
      result.spectrum_frequency_hz = spectrum.frequency_hz;
      result.spectrum_resolution_hz = spectrum.resolution_hz;
      result.spectrum_amplitude.resize(spectrum.amplitude.size(),
                                       static_cast<Eigen::Index>(n_sensors));
    }
    result.spectrum_amplitude.col(static_cast<Eigen::Index>(s)) = spectrum.amplitude;
  }
}

// Orbits: nodes with both a ux and a uy sensor (the first of each, in sensor order).
void steady_orbits(const fe::LinearSystem& system,
                   const std::vector<const model::Sensor*>& selected, TransientResult& result,
                   Eigen::Index steady_rows) {
  if (steady_rows < 3) return;
  std::vector<std::string> done;
  for (std::size_t ix = 0; ix < selected.size(); ++ix) {
    const model::Sensor& sx = *selected[ix];
    if (sx.dof != model::Component::Ux ||
        std::find(done.begin(), done.end(), sx.node) != done.end())
      continue;
    int iy = -1;
    for (std::size_t j = 0; j < selected.size() && iy < 0; ++j)
      if (selected[j]->node == sx.node && selected[j]->dof == model::Component::Uy)
        iy = static_cast<int>(j);
    if (iy < 0) continue;
    done.push_back(sx.node);
    TransientOrbit orbit =
        estimate_orbit(result.values.col(static_cast<Eigen::Index>(ix)).tail(steady_rows),
                       result.values.col(iy).tail(steady_rows));
    orbit.node = sx.node;
    orbit.sensor_x = static_cast<int>(ix);
    orbit.sensor_y = iy;
    orbit.speed_ratio = system.dofs.node(system.dofs.node_index(sx.node)).speed_ratio;
    if (orbit.speed_ratio < 0.0) orbit.whirl = signal::reversed(orbit.whirl);
    result.orbits.push_back(orbit);
  }
}

// The remainder of a least-squares fit by a constant and the harmonics at the excitation
// frequencies over the steady part, per sensor (see Steadiness).
struct FitRemainder {
  double sync_rms = 0.0, rest_rms = 0.0, rest_first = 0.0, rest_second = 0.0;
};

std::vector<FitRemainder> fit_remainders(const TransientResult& r,
                                         const std::vector<double>& omegas, Eigen::Index rows) {
  const auto n_par = static_cast<Eigen::Index>(1 + 2 * omegas.size());
  Eigen::MatrixXd A(rows, n_par);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double t = r.time[static_cast<std::size_t>(r.steady_first + i)] - r.steady_start;
    A(i, 0) = 1.0;
    for (std::size_t k = 0; k < omegas.size(); ++k) {
      A(i, static_cast<Eigen::Index>(1 + 2 * k)) = std::cos(omegas[k] * t);
      A(i, static_cast<Eigen::Index>(2 + 2 * k)) = std::sin(omegas[k] * t);
    }
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::Index half = rows / 2;
  auto rms = [](const Eigen::Ref<const Eigen::VectorXd>& v) {
    return v.size() > 0 ? std::sqrt(v.squaredNorm() / static_cast<double>(v.size())) : 0.0;
  };
  std::vector<FitRemainder> out;
  for (Eigen::Index s = 0; s < r.values.cols(); ++s) {
    const Eigen::VectorXd x = r.values.col(s).tail(rows);
    const Eigen::VectorXd c = qr.solve(x);
    const Eigen::VectorXd fit = A * c;
    const Eigen::VectorXd rest = x - fit;
    FitRemainder f;
    f.sync_rms = rms(fit.array() - c[0]);
    f.rest_rms = rms(rest);
    f.rest_first = rms(rest.head(half));
    f.rest_second = rms(rest.tail(rows - half));
    out.push_back(f);
  }
  return out;
}

Steadiness measure_steadiness(const model::Model& model, const fe::LinearSystem& system,
                              const TransientSettings& settings, const TransientResult& r,
                              Eigen::Index rows) {
  Steadiness st;
  if (!std::isnan(settings.speed_end) && settings.speed_end != settings.speed) {
    st.reason = "a run-up has no steady state";
    return st;
  }
  std::vector<double> omegas;
  if (settings.speed > 0.0)
    for (double order : fe::unbalance_orders(model, system, settings.unbalances))
      omegas.push_back(order * settings.speed);
  if (omegas.empty()) {
    st.reason = "no unbalance excitation (speed 0 or no unbalance on a spinning node)";
    return st;
  }
  const double span = r.time.back() - r.steady_start;
  const double revolution = units::kTwoPi / settings.speed;
  st.revolutions = span / revolution;
  const auto n_par = static_cast<Eigen::Index>(1 + 2 * omegas.size());
  if (st.revolutions < 4.0 || rows < 8 * n_par) {
    st.reason = fmt::format(
        "the steady part ({:.3g} revolutions, {} samples) is too short to judge: at least 4 "
        "revolutions and {} samples",
        st.revolutions, rows, 8 * n_par);
    return st;
  }
  const std::vector<FitRemainder> fits = fit_remainders(r, omegas, rows);
  double worst = -1.0;
  for (std::size_t s = 0; s < fits.size(); ++s) {
    double largest = 0.0;  // of the same unit
    for (std::size_t j = 0; j < fits.size(); ++j)
      if (r.sensor_rotational[j] == r.sensor_rotational[s])
        largest = std::max(largest, fits[j].sync_rms);
    if (!(fits[s].sync_rms > 0.0) || fits[s].sync_rms < 1e-3 * largest) continue;
    const double ratio = fits[s].rest_rms / fits[s].sync_rms;
    if (ratio <= worst) continue;
    worst = ratio;
    st.sensor = r.sensor_names[s];
    st.non_synchronous = ratio;
    const double halves = 0.5 * st.revolutions;  // revolutions between the halves' centres
    st.change_per_revolution =
        fits[s].rest_first > 0.0
            ? std::pow(fits[s].rest_second / fits[s].rest_first, 1.0 / halves) - 1.0
            : 0.0;
  }
  if (worst < 0.0) {
    st.reason = "no sensor responds at the excitation frequencies";
    return st;
  }
  st.measured = true;
  st.steady = st.non_synchronous <= Steadiness::kSteadyTolerance;
  // Decaying: the remainder falls by exp(-d t); a longer duration D + dD moves the steady part's
  // start by (1 - steady_fraction) dD.
  const double decay = -std::log1p(st.change_per_revolution) / revolution;  // [1/s]
  if (!st.steady && decay > 0.0 && settings.steady_fraction < 1.0)
    st.duration_needed =
        settings.duration + std::log(st.non_synchronous / Steadiness::kSteadyTolerance) /
                                (decay * (1.0 - settings.steady_fraction));
  return st;
}

}  // namespace

TransientResult run_transient(const model::Model& model, const TransientSettings& settings,
                              const Context& context) {
  validate(model, settings, context);
  const fe::LinearSystem& system = context.system();

  TransientResult result;
  result.settings = settings;
  // ceil, forgiving the rounding of duration / time_step (0.3 / 1e-4 = 2999.9999999999995).
  result.steps = std::max(
      1, static_cast<int>(std::ceil(settings.duration / settings.time_step * (1.0 - 1e-9))));
  result.sample_interval = settings.time_step * settings.output_every;
  const std::vector<const model::Sensor*> selected =
      select_transient_sensors(model, system, settings, result);
  integrate_record(model, system, settings, context.progress(), result);

  result.status = result.integration.status;
  if (result.status != Status::Ok) {
    result.message = "time integration stopped: " + result.integration.message;
    return result;
  }

  // Steady part: the last steady_fraction of the record.
  const double t0 = result.time.front(), t1 = result.time.back();
  const double start = t1 - settings.steady_fraction * (t1 - t0);
  const auto first =
      std::lower_bound(result.time.begin(), result.time.end(), start - 1e-9 * settings.time_step);
  result.steady_first = static_cast<int>(first - result.time.begin());
  result.steady_start = result.time[static_cast<std::size_t>(result.steady_first)];
  const Eigen::Index steady_rows =
      static_cast<Eigen::Index>(result.time.size()) - result.steady_first;
  steady_spectra(result, steady_rows);
  result.steadiness = measure_steadiness(model, system, settings, result, steady_rows);
  if (result.steadiness.steady || !result.steadiness.measured)
    steady_orbits(system, selected, result, steady_rows);
  return result;
}

namespace {

// Table "time_history" and one plot per unit.
void add_time_histories(const TransientResult& result, AnalysisOutput& out) {
  const std::size_t n_sensors = result.sensor_names.size();
  Table history;
  history.name = "time_history";
  history.title = "Sensor time histories";
  history.add("time_s", "s", result.time);
  std::vector<double> rpm(result.speed.size());
  std::transform(result.speed.begin(), result.speed.end(), rpm.begin(),
                 [](double w) { return w * kRadPerSToRpm; });
  history.add("speed_rpm", "rpm", rpm);
  for (std::size_t i = 0; i < n_sensors; ++i) {
    const Eigen::VectorXd col = result.values.col(static_cast<Eigen::Index>(i));
    history.add(result.sensor_names[i] + "_" + unit_suffix(result.sensor_rotational[i]),
                unit_suffix(result.sensor_rotational[i]),
                std::vector<double>(col.data(), col.data() + col.size()));
  }
  out.tables.push_back(std::move(history));

  for (bool rotational : {false, true}) {
    Plot plot;
    plot.name = rotational ? "time_history_rad" : "time_history_m";
    plot.title = rotational ? "Rotations" : "Displacements";
    plot.x_label = "time [s]";
    plot.y_label = rotational ? "rotation [rad]" : "displacement [m]";
    for (std::size_t i = 0; i < n_sensors; ++i) {
      if (result.sensor_rotational[i] != rotational) continue;
      Trace trace;
      trace.name = result.sensor_names[i];
      envelope(result.time, result.values.col(static_cast<Eigen::Index>(i)), trace.x, trace.y);
      plot.traces.push_back(std::move(trace));
    }
    if (!plot.traces.empty()) out.plots.push_back(std::move(plot));
  }
}

// Table and plot "spectrum" of the steady part (when computed).
void add_spectra(const TransientResult& result, AnalysisOutput& out) {
  if (result.spectrum_frequency_hz.size() == 0) return;
  Table spectrum;
  spectrum.name = "spectrum";
  const Steadiness& st = result.steadiness;
  const std::string part = st.measured && !st.steady
                               ? fmt::format("the last part (NOT steady: {:.3g} % non-synchronous)",
                                             100.0 * st.non_synchronous)
                               : std::string("the steady part");
  spectrum.title = fmt::format("Amplitude spectra (0-peak, Hann) of {}, t >= {:.6g} s", part,
                               result.steady_start);
  const Eigen::VectorXd& f = result.spectrum_frequency_hz;
  const std::vector<double> fv(f.data(), f.data() + f.size());
  spectrum.add("frequency_hz", "Hz", fv);
  Plot plot;
  plot.name = "spectrum";
  plot.title = fmt::format("Amplitude spectra of {} (0-peak)", part);
  plot.x_label = "frequency [Hz]";
  plot.y_label = "amplitude (0-peak) [m or rad]";
  plot.y_log = true;
  for (std::size_t i = 0; i < result.sensor_names.size(); ++i) {
    const Eigen::VectorXd col = result.spectrum_amplitude.col(static_cast<Eigen::Index>(i));
    spectrum.add(result.sensor_names[i] + "_" + unit_suffix(result.sensor_rotational[i]),
                 unit_suffix(result.sensor_rotational[i]),
                 std::vector<double>(col.data(), col.data() + col.size()));
    Trace trace;
    trace.name = result.sensor_names[i];
    envelope(fv, col, trace.x, trace.y);
    plot.traces.push_back(std::move(trace));
  }
  out.tables.push_back(std::move(spectrum));
  out.plots.push_back(std::move(plot));
}

// Table and plot "orbits" (when any node has both lateral sensors).
void add_orbits(const TransientResult& result, AnalysisOutput& out) {
  if (result.orbits.empty()) return;
  Table orbits;
  orbits.name = "orbits";
  orbits.title = "Orbits over the steady part (node frame e1, e2)";
  std::vector<std::string> nodes, whirl;
  std::vector<double> major, minor;
  Plot plot;
  plot.name = "orbits";
  plot.title = "Orbits over the steady part";
  plot.x_label = "x (e1) [m]";
  plot.y_label = "y (e2) [m]";
  plot.equal_aspect = true;
  const Eigen::Index steady_rows =
      static_cast<Eigen::Index>(result.time.size()) - result.steady_first;
  for (const auto& o : result.orbits) {
    nodes.push_back(o.node);
    major.push_back(o.major);
    minor.push_back(o.minor);
    whirl.emplace_back(signal::to_string(o.whirl));
    Trace trace;
    trace.name = o.node;
    const auto max_points = static_cast<Eigen::Index>(kMaxPlotPoints);
    const Eigen::Index stride =
        std::max<Eigen::Index>(1, (steady_rows + max_points - 1) / max_points);
    for (Eigen::Index k = result.steady_first; k < result.steady_first + steady_rows; k += stride) {
      trace.x.push_back(result.values(k, o.sensor_x));
      trace.y.push_back(result.values(k, o.sensor_y));
    }
    plot.traces.push_back(std::move(trace));
  }
  orbits.add_text("node", nodes);
  orbits.add("major_m", "m", major);
  orbits.add("minor_m", "m", minor);
  orbits.add_text("whirl", whirl);
  out.tables.push_back(std::move(orbits));
  out.plots.push_back(std::move(plot));
}

// How far to trust the record of a finished run: the time step against the 1x excitation, the
// spectra's resolution, run-up smearing, what the orbits are.
void add_accuracy_notes(const TransientResult& result, const fe::LinearSystem& system,
                        std::vector<std::string>& notes) {
  const auto& s = result.settings;
  const double w_max = std::isnan(s.speed_end) ? s.speed : std::max(s.speed, s.speed_end);
  double ratio_max = 0.0;
  for (const auto& node : system.dofs.nodes())
    ratio_max = std::max(ratio_max, std::abs(node.speed_ratio));
  const double w_exc = w_max * std::max(ratio_max, 1.0);
  if (w_exc > 0.0) {
    const double wh = w_exc * s.time_step;
    notes.push_back(fmt::format(
        "at the highest 1x excitation frequency, {:.4g} Hz, omega h = {:.3g}: the scheme's "
        "relative period (phase) error is about (omega h)^2 / 12 = {:.2g}, the amplitude error "
        "of a forced response of the same order",
        w_exc / units::kTwoPi, wh, wh * wh / 12.0));
    if (w_exc * result.sample_interval > units::kPi / 4)
      notes.push_back(fmt::format(
          "the stored samples (every {} steps, {:.4g} Hz) hold fewer than 8 per period of the "
          "1x excitation: lower output_every for usable spectra and orbits",
          s.output_every, 1.0 / result.sample_interval));
  }
  if (result.spectrum_frequency_hz.size() > 0)
    notes.push_back(fmt::format(
        "steady part t = {:.6g} .. {:.6g} s ({} samples); spectra: Hann window, resolution "
        "{:.4g} Hz, 0-peak amplitude with coherent-gain correction; a component between two "
        "bins reads up to {:.1f} % low",
        result.steady_start, result.time.back(),
        static_cast<long>(result.time.size()) - result.steady_first, result.spectrum_resolution_hz,
        100 * signal::max_scalloping_loss(signal::Window::Hann)));
  else
    notes.push_back(fmt::format("the steady part holds fewer than {} samples: no spectra",
                                kMinSpectrumSamples));
  if (!std::isnan(s.speed_end) && s.speed_end != s.speed)
    notes.push_back(
        "run-up: the speed changes over the 'steady' part, so its spectra are smeared over the "
        "speeds it spans and its orbits are not steady");
  if (!result.orbits.empty())
    notes.push_back(
        "orbits: major/minor are the largest/smallest distances from the orbit's centre (middle "
        "of its bounding box) over the steady part, the semi-axes for a single-frequency "
        "orbit; whirl relative to the spin");
}

// Whether the steady part is steady, and what to change when it is not.
std::string steadiness_note(const TransientResult& result) {
  const Steadiness& st = result.steadiness;
  if (!st.measured) return "steadiness of the steady part not measured: " + st.reason;
  const std::string measure = fmt::format(
      "non-synchronous content (RMS of what a constant plus the excitation harmonics order x "
      "speed do not fit over the steady part, relative to the harmonics' RMS) {:.3g} % at "
      "sensor '{}' ({:.4g} revolutions), changing by {:+.3g} % per revolution",
      100.0 * st.non_synchronous, st.sensor, st.revolutions, 100.0 * st.change_per_revolution);
  if (st.steady)
    return fmt::format("steady part steady: {} (limit {:g} %)", measure,
                       100.0 * Steadiness::kSteadyTolerance);
  return fmt::format(
      "NOT steady: {} (limit {:g} %): the start-up transient has not died out, so no orbits are "
      "given and the spectra show the transient too; {}",
      measure, 100.0 * Steadiness::kSteadyTolerance,
      std::isfinite(st.duration_needed)
          ? fmt::format("raise duration to about {:.3g} s (from the decay measured), or add "
                        "damping",
                        st.duration_needed)
          : std::string("the remainder does not decay: check the stability of the system"));
}

}  // namespace

AnalysisOutput transient_output(const model::Model& /*model*/,
                                const TransientSettings& /*settings*/,
                                const TransientResult& result, const Context& context) {
  const fe::LinearSystem& system = context.system();
  AnalysisOutput out;
  out.name = context.name();
  out.type = "transient";
  out.status = result.status;
  out.message = result.message;
  add_time_histories(result, out);
  add_spectra(result, out);
  add_orbits(result, out);

  // How far to trust it.
  out.notes.push_back(
      "cost estimate before the run: " +
      estimate_cost(result.settings, static_cast<int>(result.sensor_names.size())).describe() +
      fmt::format(" (refused above {:.0e} steps or a {:.0f} GB time history)",
                  TransientCost::kMaxSteps, TransientCost::kMaxOutputBytes / 1e9));
  out.notes.push_back("integration: " + result.integration.brief_report());
  if (result.integration.steps_taken > 0 && !result.integration.solver.empty())
    out.notes.push_back("iteration matrix factorised with " + result.integration.solver);
  if (result.status == Status::Ok) {
    out.notes.insert(out.notes.begin(), steadiness_note(result));
    add_accuracy_notes(result, system, out.notes);
  }
  if (system.K_loss.nonZeros() > 0 && system.K_loss.norm() > 0.0)
    out.notes.push_back(
        "the model's hysteretic (structural) loss factors have no time-domain equivalent and are "
        "not in this run: only viscous, Rayleigh and modal damping act; give Rayleigh or modal "
        "damping for a transient comparable with the harmonic analyses");
  for (std::size_t i = 0; i < result.sensor_names.size(); ++i)
    if (result.sensor_equations[i] < 0)
      out.notes.push_back("sensor '" + result.sensor_names[i] +
                          "' measures a constrained DOF and reads 0");
  return out;
}

TransientSensorSummary summarize_sensor(const TransientResult& result, const std::string& sensor) {
  std::size_t s = 0;
  while (s < result.sensor_names.size() && result.sensor_names[s] != sensor) ++s;
  if (s == result.sensor_names.size())
    throw std::runtime_error(fmt::format("sensor '{}' is not recorded by this analysis", sensor));
  if (result.status != Status::Ok || result.time.empty())
    throw std::runtime_error("the time integration did not finish: " + result.message);
  TransientSensorSummary summary;
  summary.unit = unit_suffix(result.sensor_rotational[s]);
  const auto col = result.values.col(static_cast<Eigen::Index>(s));
  Eigen::Index at = 0;
  summary.peak = col.cwiseAbs().maxCoeff(&at);
  summary.peak_speed = result.speed[static_cast<std::size_t>(at)];
  summary.peak_time = result.time[static_cast<std::size_t>(at)];
  const Eigen::Index steady_rows = col.size() - result.steady_first;
  summary.steady_rms = std::sqrt(col.tail(steady_rows).squaredNorm() / steady_rows);
  return summary;
}

}  // namespace geardyn::analyses
