// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geardyn/analyses/nonlinear_condensed.hpp"
#include "geardyn/analyses/nonlinear_elements.hpp"
#include "geardyn/analyses/nonlinear_forcing.hpp"
#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/periodic_time.hpp"
#include "geardyn/hbm/stability.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The force level continuation: R(X, lambda) = R_hb(X, omega) - (lambda - 1) F_ext at a fixed
// omega (the balance's own load factor is 1), dR/dlambda = -F_ext.
class LevelSystem final : public hbm::HarmonicSystem {
 public:
  LevelSystem(const hbm::ElementHarmonicBalance& hb, double omega) : hb_(hb), omega_(omega) {}
  int size() const override { return hb_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double lambda, Eigen::MatrixXd* J,
                           Eigen::VectorXd* dR) const override {
    Eigen::VectorXd R = hb_.residual(X, omega_, J) - (lambda - 1.0) * hb_.external_force();
    if (dR != nullptr) *dR = -hb_.external_force();
    return R;
  }
  double residual_scale(const Eigen::VectorXd& X, double lambda) const override {
    return std::max(hb_.residual_scale(X, omega_), std::abs(lambda) * hb_.external_force().norm());
  }

 private:
  const hbm::ElementHarmonicBalance& hb_;
  double omega_;
};

// Fourier coefficients of the excitation on the equations: named forces at the fundamental
// (a_1 = A cos phi, b_1 = -A sin phi: f = Re(A e^{i phi} e^{i w t})) and constant loads.
Eigen::MatrixXd excitation_of(const model::Model& model, const fe::LinearSystem& system,
                              const NonlinearResponseSettings& s) {
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(system.size(), 3);  // [a0, a1, b1] per equation
  auto force_of = [&](const std::string& name) -> const model::HarmonicForce& {
    for (const auto& f : model.forces)
      if (f.name == name) return f;
    throw std::logic_error("unknown force " + name);  // the parser checked the names
  };
  auto node_index = [&](const std::string& node) { return system.dofs.node_index(node); };
  for (const auto& name : s.forces) {
    const auto& f = force_of(name);
    const Eigen::VectorXd unit = system.unit_load(node_index(f.node), f.dof);
    F.col(1) += f.amplitude * std::cos(f.phase) * unit;
    F.col(2) -= f.amplitude * std::sin(f.phase) * unit;
  }
  for (const auto& name : s.mean_forces) {
    const auto& f = force_of(name);
    F.col(0) += f.amplitude * std::cos(f.phase) * system.unit_load(node_index(f.node), f.dof);
  }
  return F;
}

// Scales of the arc length: the linear response's size over the range and the range itself.
void set_scales(const ForcedBalance& forced, const hbm::ElementHarmonicBalance& hb,
                const NonlinearResponseSettings& s, hbm::ContinuationOptions& o) {
  double x = 0.0;
  if (s.parameter != ContinuationParameter::ForceLevel) {  // frequency or speed
    for (int k = 0; k <= 20; ++k) {
      const double p = o.omega_start + (o.omega_end - o.omega_start) * k / 20.0;
      if (p <= 0.0) continue;
      try {
        x = std::max(x, forced.linear_response(p).norm());
      } catch (...) {  // a singular linear structure at that frequency: no scale from it
      }
    }
    o.omega_scale = o.omega_end - o.omega_start;
  } else {
    x = hb.linear_response(s.frequency).norm() * std::max(std::abs(s.level_stop), 1e-12);
    o.omega_scale = std::abs(s.level_stop - s.level_start);
  }
  o.x_scale = std::isfinite(x) && x > 0.0 ? x : 1.0;
}

// The range, steps, tolerance and scales of the continuation over the settings' parameter.
hbm::ContinuationOptions continuation_options(const ForcedBalance& forced,
                                              const hbm::ElementHarmonicBalance& hb,
                                              const NonlinearResponseSettings& s) {
  hbm::ContinuationOptions o;
  const bool frequency = s.parameter == ContinuationParameter::Frequency;
  const bool by_speed = s.parameter == ContinuationParameter::Speed;
  o.omega_start = frequency ? s.f_start : by_speed ? s.speed_start : s.level_start;
  o.omega_end = frequency ? s.f_stop : by_speed ? s.speed_stop : s.level_stop;
  o.step = s.step;
  o.max_step = s.max_step;
  o.max_points = s.max_points;
  o.tolerance = s.tolerance;
  set_scales(forced, hb, s, o);
  return o;
}

}  // namespace

// The continuation stops at the first point past the end of the range: that point is moved
// onto the end by interpolating between the last two and a Newton correction at the fixed
// parameter (kept as traced when Newton does not converge).
void land_on_end(const hbm::HarmonicSystem& system, double end, double tolerance,
                 std::vector<hbm::ContinuationPoint>& points) {
  if (points.size() < 2) return;
  hbm::ContinuationPoint& last = points.back();
  const hbm::ContinuationPoint& before = points[points.size() - 2];
  if (last.omega == end || (last.omega - end) * (before.omega - end) > 0.0) return;
  const double s = (end - before.omega) / (last.omega - before.omega);
  Eigen::VectorXd X = before.X + s * (last.X - before.X);
  Eigen::MatrixXd J;
  for (int it = 1; it <= 20; ++it) {
    const Eigen::VectorXd R = system.residual(X, end, &J);
    if (!R.allFinite()) return;
    if (R.norm() <= tolerance * system.residual_scale(X, end)) {
      last = {end, X, it, R.norm()};
      return;
    }
    X -= J.partialPivLu().solve(R);
  }
}

// Turning points of the continuation parameter p along the curve. Contact laws make the curve
// ripple near a fold (turns a fraction of a per mil of the range apart); turns closer than
// `merge` in p form one cluster, which is one turning point when it has an odd number of turns
// (at its first turn) and none when even.
std::vector<int> turning_points(const std::vector<double>& p, double merge) {
  std::vector<int> raw;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double a = p[i] - p[i - 1], b = p[i + 1] - p[i];
    if (a * b < 0.0) raw.push_back(static_cast<int>(i));
  }
  std::vector<int> out;
  for (std::size_t k = 0; k < raw.size();) {
    std::size_t end = k + 1;
    while (end < raw.size() && std::abs(p[static_cast<std::size_t>(raw[end])] -
                                        p[static_cast<std::size_t>(raw[end - 1])]) <= merge)
      ++end;
    if ((end - k) % 2 == 1) out.push_back(raw[k]);
    k = end;
  }
  return out;
}

// Unstable after an odd number of turning points (a real multiplier crosses +1 at each fold;
// Seydel 2010, ch. 7), from a stable start.
std::vector<char> unstable_after(const std::vector<int>& turns, std::size_t points) {
  std::vector<char> u(points, 0);
  std::size_t next = 0;
  bool odd = false;
  for (std::size_t i = 0; i < points; ++i) {
    while (next < turns.size() && static_cast<std::size_t>(turns[next]) < i) {
      odd = !odd;
      ++next;
    }
    u[i] = odd ? 1 : 0;
  }
  return u;
}

namespace {

void record_point(const hbm::ElementHarmonicBalance& hb, const Eigen::MatrixXd& sensors_q,
                  const hbm::ContinuationPoint& p, double omega, double level, double scale,
                  NonlinearResponseResult& r) {
  const int s = hb.basis().size(), n = hb.system().dofs();
  const Eigen::Map<const Eigen::MatrixXd> Xs(p.X.data(), s, n);
  r.sensor_coefficients.push_back(sensors_q * Xs.transpose());
  r.frequency.push_back(omega);
  r.level.push_back(level);
  r.iterations.push_back(p.iterations);
  r.residual.push_back(p.residual / scale);
}

void element_statistics(const hbm::ElementHarmonicBalance& hb,
                        const std::vector<hbm::ContinuationPoint>& points,
                        NonlinearResponseResult& r) {
  const auto np = static_cast<Eigen::Index>(points.size());
  const auto ne = static_cast<Eigen::Index>(hb.system().elements.size());
  r.energy.setConstant(np, ne, kNaN);
  r.stick = r.slip = r.open = r.energy;
  for (Eigen::Index i = 0; i < np; ++i)
    for (Eigen::Index e = 0; e < ne; ++e) {
      const auto& placed = hb.system().elements[static_cast<std::size_t>(e)];
      const hbm::ElementLoop loop = placed.element->loop(
          hb.basis(),
          hb.element_coordinates(points[static_cast<std::size_t>(i)].X, static_cast<int>(e)),
          r.frequency[static_cast<std::size_t>(i)]);
      r.energy(i, e) = loop.energy_per_cycle;
      r.stick(i, e) = loop.stick_fraction;
      r.slip(i, e) = loop.slip_fraction;
      r.open(i, e) = loop.open_fraction;
    }
}

}  // namespace

// Point i's Floquet verdict (Hill or monodromy); a failed eigen-solve is labelled "failed".
void record_floquet(const hbm::FloquetResult& f, std::size_t i, NonlinearResponseResult& r) {
  r.max_real_exponent[i] = f.max_real_part;
  r.unstable[i] = f.status == Status::Ok && !f.stable ? 1 : 0;
  r.instability[i] = f.status == Status::Ok ? hbm::to_string(f.kind) : "failed";
}

namespace {

void stability(const hbm::ElementHarmonicBalance& hb, const ForcedBalance& forced,
               const NonlinearResponseSettings& s,
               const std::vector<hbm::ContinuationPoint>& points, const Context& context,
               NonlinearResponseResult& r) {
  const std::size_t np = points.size();
  r.max_real_exponent.assign(np, kNaN);
  r.instability.assign(np, "");
  if (s.stability == NonlinearStability::Fold) {
    r.unstable = unstable_after(r.turning_points, np);
    for (std::size_t i = 0; i < np; ++i) r.instability[i] = r.unstable[i] ? "fold" : "none";
    return;
  }
  r.unstable.assign(np, 0);
  // The balance of point i: the structure and excitation at its speed or frequency when they
  // move with the parameter (nonlinear_forcing.hpp), else the one balance.
  std::optional<hbm::ElementHarmonicBalance> moved;
  auto at = [&](std::size_t i) -> const hbm::ElementHarmonicBalance& {
    if (!forced.moves() || s.parameter == ContinuationParameter::ForceLevel) return hb;
    return moved.emplace(forced.balance_at(points[i].omega));
  };
  if (s.stability == NonlinearStability::Monodromy) {
    hbm::MonodromyOptions o;
    o.march.steps_per_period = 1024;
    for (std::size_t i = 0; i < np; ++i) {
      o.march.load_factor = r.level[i];
      hbm::FloquetResult f;
      try {
        f = hbm::monodromy_stability(at(i).system(), r.frequency[i], points[i].X, hb.basis(), o);
      } catch (const InputError& e) {
        throw context.error("stability", "a system the time march can integrate",
                            e.expected() + " not met: " + e.found(), "use stability = \"fold\"");
      }
      record_floquet(f, i, r);
    }
    return;
  }
  // Hill's method with the elements' velocity Jacobian in the first-order term (friction
  // regularised by tanh, squeeze films, dampers in contacts): hbm/stability.hpp.
  for (std::size_t i = 0; i < np; ++i) {
    const hbm::FloquetResult f = hbm::hill_stability(at(i), points[i].X, r.frequency[i]);
    record_floquet(f, i, r);
  }
}

}  // namespace

// The point of largest sensor RMS (or of the largest coefficient norm without sensors).
int largest_point(const NonlinearResponseResult& r) {
  int best = -1;
  double value = -1.0;
  for (std::size_t i = 0; i < r.sensor_coefficients.size(); ++i) {
    const Eigen::MatrixXd& c = r.sensor_coefficients[i];
    double v = 0.0;
    for (Eigen::Index k = 0; k < c.rows(); ++k) v = std::max(v, series_rms(c.row(k).transpose()));
    if (v > value) {
      value = v;
      best = static_cast<int>(i);
    }
  }
  return best;
}

double harmonic_amplitude(const Eigen::VectorXd& c, int n) {
  if (n == 0) return std::abs(c[0]);
  return std::hypot(c[hbm::HarmonicBasis::cos_index(n)], c[hbm::HarmonicBasis::sin_index(n)]);
}

double series_rms(const Eigen::VectorXd& c) {
  if (c.size() == 0) return 0.0;
  // a_0^2 + sum (a_n^2 + b_n^2) / 2 = (||c||^2 + a_0^2) / 2.
  const double all = c.squaredNorm(), mean = c.head(1).squaredNorm();
  return std::sqrt(0.5 * (all + mean));
}

NonlinearResponseResult run_nonlinear_response(const model::Model& model,
                                               const NonlinearResponseSettings& s,
                                               const Context& context) {
  NonlinearResponseResult r;
  r.parameter = s.parameter;
  fe::LinearSystem own;
  const fe::LinearSystem& system = nonlinear_structure(model, context, own);

  const std::vector<BuiltNonlinearElement> elements =
      build_nonlinear_elements(model, system, context);
  const NonlinearCoordinates c = nonlinear_coordinates(system, s.speed, s.n_modes, context);
  const NonlinearForcing forcing = nonlinear_forcing(model, system, s, s.harmonics, context);
  const Eigen::MatrixXd F = excitation_of(model, system, s) + forcing.fixed;
  const SensorRows sensors = nonlinear_sensor_rows(model, system, s.sensors, context);
  if (s.form == NonlinearForm::Condensed)
    return run_nonlinear_condensed({system, elements, c, F, sensors}, s, context);
  r.sensors = sensors.names;
  r.sensor_rotational = sensors.rotational;
  for (const auto& e : elements) {
    r.elements.push_back(e.name);
    r.element_kinds.push_back(e.kind);
  }
  r.modal = c.modal;
  r.highest_mode_hz = c.highest_mode / units::kTwoPi;
  r.coordinates = static_cast<int>(c.M.rows());
  r.harmonics = s.harmonics;
  r.time_samples = s.time_samples > 0 ? s.time_samples : hbm::default_time_samples(s.harmonics);
  if (r.time_samples < 2 * s.harmonics + 1)
    throw context.error("time_samples", fmt::format("at least 2 H + 1 = {}", 2 * s.harmonics + 1),
                        fmt::format("{}", s.time_samples));
  const hbm::ElementHarmonicBalance hb(placed_element_system(c, elements, F),
                                       hbm::HarmonicBasis(s.harmonics, r.time_samples));
  const ForcedBalance forced(system, c, hb, forcing, s);

  const bool frequency = s.parameter == ContinuationParameter::Frequency;
  const bool by_speed = s.parameter == ContinuationParameter::Speed;
  const hbm::ContinuationOptions o = continuation_options(forced, hb, s);
  const Eigen::VectorXd X0 = Eigen::VectorXd::Zero(hb.size());
  const LevelSystem level(hb, s.frequency);
  const hbm::HarmonicSystem& traced = s.parameter == ContinuationParameter::ForceLevel
                                          ? static_cast<const hbm::HarmonicSystem&>(level)
                                          : forced;
  hbm::ContinuationResult curve = hbm::continue_in_frequency(traced, X0, o);
  if (curve.status == Status::Ok) land_on_end(traced, o.omega_end, o.tolerance, curve.points);
  if (curve.points.empty()) {
    throw NumericalError(
        context.name(),
        fmt::format("the harmonic balance could not start at {}: {}. Start where the response "
                    "is nearly linear (away from resonance, or at a lower force level), or give "
                    "the mean loads that close the contacts (mean_forces).",
                    frequency  ? fmt::format("{:.6g} Hz", s.f_start / units::kTwoPi)
                    : by_speed ? fmt::format("{:.6g} rpm", s.speed_start * 60.0 / units::kTwoPi)
                               : fmt::format("force factor {:.6g}", s.level_start),
                    curve.message));
  }
  const Eigen::MatrixXd sensors_q = sensors.rows * c.basis;
  for (const auto& p : curve.points) {
    const bool level_p = s.parameter == ContinuationParameter::ForceLevel;
    record_point(hb, sensors_q, p, level_p ? s.frequency : forced.fundamental(p.omega),
                 level_p ? p.omega : 1.0, traced.residual_scale(p.X, p.omega), r);
    r.speed.push_back(level_p ? s.speed : forced.speed(p.omega));
  }
  element_statistics(hb, curve.points, r);
  r.turning_points = turning_points(frequency  ? r.frequency
                                    : by_speed ? r.speed
                                               : r.level,
                                    1e-3 * std::abs(o.omega_end - o.omega_start));
  r.branch_points = curve.branch_points;
  stability(hb, forced, s, curve.points, context, r);
  r.loop_point = largest_point(r);
  if (r.loop_point >= 0)
    for (std::size_t e = 0; e < elements.size(); ++e)
      r.loops.push_back(hb.system().elements[e].element->loop(
          hb.basis(),
          hb.element_coordinates(curve.points[static_cast<std::size_t>(r.loop_point)].X,
                                 static_cast<int>(e)),
          r.frequency[static_cast<std::size_t>(r.loop_point)]));
  mark_ended_early(curve, r);
  return r;
}

void mark_ended_early(const hbm::ContinuationResult& curve, NonlinearResponseResult& r) {
  if (curve.status == Status::Ok) return;
  r.status = Status::NotConverged;
  r.message = fmt::format(
      "the continuation ended before the end of the range: {}. The points up to there are "
      "converged solutions.",
      curve.message);
}

}  // namespace geardyn::analyses
