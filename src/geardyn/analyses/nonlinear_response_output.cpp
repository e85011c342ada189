// Tables, plots and notes of the `nonlinear_response` analysis (nonlinear_response.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/analyses/nonlinear_response.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string unit_of(const NonlinearResponseResult& r, std::size_t s) {
  return r.sensor_rotational[s] ? "rad" : "m";
}

bool by_frequency(const NonlinearResponseResult& r) {
  return r.parameter == ContinuationParameter::Frequency;
}

bool by_speed(const NonlinearResponseResult& r) {
  return r.parameter == ContinuationParameter::Speed;
}

// The continuation parameter of point i as plotted: Hz, rpm or the force factor.
double abscissa(const NonlinearResponseResult& r, std::size_t i) {
  if (by_speed(r)) return r.speed[i] * 60.0 / units::kTwoPi;
  return by_frequency(r) ? r.frequency[i] / units::kTwoPi : r.level[i];
}

std::string abscissa_label(const NonlinearResponseResult& r) {
  if (by_speed(r)) return "speed [rpm]";
  return by_frequency(r) ? "fundamental frequency [Hz]" : "force factor [-]";
}

// Largest |x(theta)| over a fine sampling of the period.
double peak_of(const Eigen::VectorXd& c, const hbm::HarmonicBasis& fine) {
  return fine.to_time(c).cwiseAbs().maxCoeff();
}

Table response_table(const NonlinearResponseResult& r) {
  Table t;
  t.name = "nonlinear_response";
  t.title =
      "Periodic response along the continuation (amplitudes of the first harmonic, RMS "
      "and peak over the period)";
  const std::size_t np = r.frequency.size();
  std::vector<double> point(np), hz(np), stable(np);
  for (std::size_t i = 0; i < np; ++i) {
    point[i] = static_cast<double>(i);
    hz[i] = r.frequency[i] / units::kTwoPi;
    stable[i] = r.unstable[i] ? 0.0 : 1.0;
  }
  t.add("point", "", point);
  t.add("frequency_hz", "Hz", hz);
  t.add("force_factor", "", r.level);
  if (by_speed(r)) {
    std::vector<double> rpm(np);
    for (std::size_t i = 0; i < np; ++i) rpm[i] = abscissa(r, i);
    t.add("speed_rpm", "rpm", rpm);
  }
  t.add("stable", "", stable);
  t.add_text("instability", r.instability);
  if (std::any_of(r.max_real_exponent.begin(), r.max_real_exponent.end(),
                  [](double x) { return std::isfinite(x); }))
    t.add("max_real_exponent_per_s", "1/s", r.max_real_exponent);
  std::vector<double> iterations(r.iterations.begin(), r.iterations.end());
  t.add("newton_iterations", "", iterations);
  t.add("relative_residual", "", r.residual);
  const hbm::HarmonicBasis fine(r.harmonics, std::max(256, 8 * r.harmonics + 8));
  for (std::size_t s = 0; s < r.sensors.size(); ++s) {
    std::vector<double> h1(np), rms(np), peak(np);
    for (std::size_t i = 0; i < np; ++i) {
      const Eigen::VectorXd c = r.sensor_coefficients[i].row(static_cast<Eigen::Index>(s));
      h1[i] = harmonic_amplitude(c, 1);
      rms[i] = series_rms(c);
      peak[i] = peak_of(c, fine);
    }
    const std::string u = unit_of(r, s);
    t.add(fmt::format("{}_h1_{}", r.sensors[s], u), u, h1);
    t.add(fmt::format("{}_rms_{}", r.sensors[s], u), u, rms);
    t.add(fmt::format("{}_peak_{}", r.sensors[s], u), u, peak);
  }
  return t;
}

Table harmonics_table(const NonlinearResponseResult& r) {
  Table t;
  t.name = "harmonics";
  t.title =
      "Amplitude and phase of every harmonic at every sensor (cosine phase: x_n(t) = A_n "
      "cos(n w t + phi_n); n = 0 is the mean)";
  std::vector<double> point, hz, harmonic, amplitude, phase;
  std::vector<std::string> sensor;
  for (std::size_t i = 0; i < r.frequency.size(); ++i)
    for (std::size_t s = 0; s < r.sensors.size(); ++s) {
      const Eigen::VectorXd c = r.sensor_coefficients[i].row(static_cast<Eigen::Index>(s));
      for (int n = 0; n <= r.harmonics; ++n) {
        point.push_back(static_cast<double>(i));
        hz.push_back(r.frequency[i] / units::kTwoPi);
        sensor.push_back(r.sensors[s]);
        harmonic.push_back(n);
        if (n == 0) {
          amplitude.push_back(c[0]);
          phase.push_back(0.0);
        } else {
          const double a = c[hbm::HarmonicBasis::cos_index(n)];
          const double b = c[hbm::HarmonicBasis::sin_index(n)];
          amplitude.push_back(std::hypot(a, b));
          phase.push_back(std::atan2(-b, a) / units::kRadPerDegree);
        }
      }
    }
  t.add("point", "", point);
  t.add("frequency_hz", "Hz", hz);
  t.add_text("sensor", sensor);
  t.add("harmonic", "", harmonic);
  t.add("amplitude", "m or rad", amplitude);
  t.add("phase_deg", "deg", phase);
  return t;
}

bool any_finite(const Eigen::VectorXd& v) { return v.array().isFinite().any(); }

Table energy_table(const NonlinearResponseResult& r) {
  Table t;
  t.name = "element_energy";
  t.title =
      "Energy dissipated per cycle by each element, and the share of the period in each "
      "regime (stick / slip / open where the element has them)";
  std::vector<double> hz(r.frequency.size());
  for (std::size_t i = 0; i < hz.size(); ++i) hz[i] = r.frequency[i] / units::kTwoPi;
  t.add("frequency_hz", "Hz", hz);
  t.add("force_factor", "", r.level);
  auto column = [](const Eigen::VectorXd& v) { return std::vector<double>(v.begin(), v.end()); };
  for (std::size_t e = 0; e < r.elements.size(); ++e) {
    const auto k = static_cast<Eigen::Index>(e);
    t.add(r.elements[e] + "_energy_j", "J", column(r.energy.col(k)));
    if (any_finite(r.stick.col(k))) t.add(r.elements[e] + "_stick", "", column(r.stick.col(k)));
    if (any_finite(r.slip.col(k))) t.add(r.elements[e] + "_slip", "", column(r.slip.col(k)));
    if (any_finite(r.open.col(k))) t.add(r.elements[e] + "_open", "", column(r.open.col(k)));
  }
  return t;
}

// The points `at` of the curve: parameter values and first-harmonic amplitudes.
Table points_table(const NonlinearResponseResult& r, const std::vector<int>& at, std::string name,
                   std::string title) {
  Table t;
  t.name = std::move(name);
  t.title = std::move(title);
  std::vector<double> point, hz, level;
  for (int i : at) {
    const auto k = static_cast<std::size_t>(i);
    point.push_back(i);
    hz.push_back(r.frequency[k] / units::kTwoPi);
    level.push_back(r.level[k]);
  }
  t.add("point", "", point);
  t.add("frequency_hz", "Hz", hz);
  t.add("force_factor", "", level);
  for (std::size_t s = 0; s < r.sensors.size(); ++s) {
    std::vector<double> h1;
    for (int i : at)
      h1.push_back(harmonic_amplitude(
          r.sensor_coefficients[static_cast<std::size_t>(i)].row(static_cast<Eigen::Index>(s)), 1));
    t.add(fmt::format("{}_h1_{}", r.sensors[s], unit_of(r, s)), unit_of(r, s), h1);
  }
  return t;
}

Table turning_table(const NonlinearResponseResult& r) {
  return points_table(r, r.turning_points, "turning_points",
                      "Turning points of the response curve (folds: the jump frequencies of a "
                      "sweep)");
}

Table branch_table(const NonlinearResponseResult& r) {
  return points_table(r, r.branch_points, "branch_points",
                      "Branch points (simple bifurcations of the same period: another family of "
                      "periodic solutions crosses the curve between this point and the one "
                      "before; e.g. a symmetry-breaking response)");
}

Table loops_table(const NonlinearResponseResult& r) {
  Table t;
  t.name = "hysteresis_loops";
  t.title = r.loop_point < 0
                ? std::string("Element force over displacement (no point)")
                : fmt::format(
                      "Element force over its displacement over one period at the point "
                      "of largest response ({:.6g} Hz)",
                      r.frequency[static_cast<std::size_t>(r.loop_point)] / units::kTwoPi);
  std::vector<std::string> element;
  std::vector<double> coordinate, phase, u, f;
  for (std::size_t e = 0; e < r.loops.size(); ++e) {
    const hbm::ElementLoop& loop = r.loops[e];
    const Eigen::Index n = loop.displacement.rows();
    for (Eigen::Index k = 0; k < loop.displacement.cols(); ++k)
      for (Eigen::Index j = 0; j <= n; ++j) {  // closed: sample 0 repeated at the end
        const Eigen::Index jj = j % n;
        element.push_back(r.elements[e]);
        coordinate.push_back(static_cast<double>(k));
        phase.push_back(360.0 * static_cast<double>(j) / static_cast<double>(n));
        u.push_back(loop.displacement(jj, k));
        f.push_back(loop.force(jj, k));
      }
  }
  t.add_text("element", element);
  t.add("coordinate", "", coordinate);
  t.add("phase_deg", "deg", phase);
  t.add("displacement", "m or rad", u);
  t.add("force", "N or N m", f);
  return t;
}

// A curve split into its stable (solid) and unstable (dashed) stretches.
void add_curve(Plot& p, const std::string& name, const std::vector<double>& x,
               const std::vector<double>& y, const std::vector<char>& unstable) {
  Trace solid, dashed;
  solid.name = name;
  dashed.name = name + " (unstable)";
  dashed.dash = "dash";
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool u = unstable[i] != 0;
    // Stretches join at their ends: a point next to a change belongs to both.
    const bool u_prev = i > 0 && unstable[i - 1] != 0;
    solid.x.push_back(!u || (i > 0 && !u_prev) ? x[i] : kNaN);
    solid.y.push_back(!u || (i > 0 && !u_prev) ? y[i] : kNaN);
    dashed.x.push_back(u || u_prev ? x[i] : kNaN);
    dashed.y.push_back(u || u_prev ? y[i] : kNaN);
  }
  p.traces.push_back(solid);
  if (std::any_of(unstable.begin(), unstable.end(), [](char c) { return c != 0; }))
    p.traces.push_back(dashed);
}

std::vector<Plot> plots(const NonlinearResponseResult& r) {
  std::vector<Plot> out;
  const std::size_t np = r.frequency.size();
  std::vector<double> x(np);
  for (std::size_t i = 0; i < np; ++i) x[i] = abscissa(r, i);
  Plot rms;
  rms.name = "response";
  rms.title = "RMS response over the period (dashed: unstable)";
  rms.x_label = abscissa_label(r);
  rms.y_label = "RMS [m or rad]";
  for (std::size_t s = 0; s < r.sensors.size(); ++s) {
    std::vector<double> y(np);
    for (std::size_t i = 0; i < np; ++i)
      y[i] = series_rms(r.sensor_coefficients[i].row(static_cast<Eigen::Index>(s)));
    add_curve(rms, r.sensors[s], x, y, r.unstable);
  }
  out.push_back(rms);
  if (!r.elements.empty()) {
    Plot e;
    e.name = "element_energy";
    e.title = "Energy dissipated per cycle";
    e.x_label = abscissa_label(r);
    e.y_label = "energy per cycle [J]";
    for (std::size_t k = 0; k < r.elements.size(); ++k) {
      Trace tr;
      tr.name = r.elements[k];
      tr.x = x;
      const Eigen::VectorXd c = r.energy.col(static_cast<Eigen::Index>(k));
      tr.y.assign(c.begin(), c.end());
      e.traces.push_back(tr);
    }
    out.push_back(e);
  }
  if (!r.loops.empty()) {
    Plot l;
    l.name = "hysteresis_loops";
    l.title = "Hysteresis loops at the largest response (coordinate 0 of each element)";
    l.x_label = "displacement [m or rad]";
    l.y_label = "force [N or N m]";
    for (std::size_t k = 0; k < r.loops.size(); ++k) {
      Trace tr;
      tr.name = r.elements[k];
      const auto& loop = r.loops[k];
      for (Eigen::Index j = 0; j <= loop.displacement.rows(); ++j) {
        tr.x.push_back(loop.displacement(j % loop.displacement.rows(), 0));
        tr.y.push_back(loop.force(j % loop.displacement.rows(), 0));
      }
      l.traces.push_back(tr);
    }
    out.push_back(l);
  }
  return out;
}

std::vector<std::string> notes(const NonlinearResponseResult& r) {
  std::vector<std::string> n;
  n.push_back(
      fmt::format("Harmonic balance with H = {} harmonics and {} time samples per period "
                  "(alternating frequency-time), {} {}; {} continuation points.",
                  r.harmonics, r.time_samples, r.coordinates,
                  r.condensed ? "element coordinates (condensed)"
                  : r.modal   ? "modal coordinates"
                              : "physical DOFs",
                  r.frequency.size()));
  n.insert(n.end(), r.notes.begin(), r.notes.end());
  if (r.modal)
    n.push_back(
        fmt::format("Modal form: the highest mode kept is at {:.6g} Hz; the static "
                    "contribution of the modes above is left out, so it should lie well "
                    "above H x the highest fundamental.",
                    r.highest_mode_hz));
  if (!r.residual.empty())
    n.push_back(fmt::format("Largest relative residual of a converged point: {:.3g}.",
                            *std::max_element(r.residual.begin(), r.residual.end())));
  const auto unstable = std::count(r.unstable.begin(), r.unstable.end(), 1);
  if (!r.branch_points.empty())
    n.push_back(fmt::format(
        "{} branch point(s) on the curve (table branch_points): another family of periodic "
        "solutions crosses it there, which this continuation does not follow; the stability "
        "changes at each, which the \"fold\" verdict does not count (use stability = \"hill\" "
        "or \"monodromy\").",
        r.branch_points.size()));
  else if (r.condensed)
    n.push_back(
        "Branch points are not detected in the condensed form (its Newton systems are "
        "solved iteratively, without the determinant the test needs).");
  n.push_back(
      fmt::format("{} turning point(s); {} of {} points unstable ({}).", r.turning_points.size(),
                  unstable, r.unstable.size(),
                  r.max_real_exponent.empty() || !std::isfinite(r.max_real_exponent.front())
                      ? "from the turning points: a real Floquet multiplier crosses +1 at each fold"
                      : "Hill's method on the harmonic-balance Jacobian"));
  return n;
}

}  // namespace

AnalysisOutput nonlinear_response_output(const model::Model& /*model*/,
                                         const NonlinearResponseSettings& /*settings*/,
                                         const NonlinearResponseResult& r, const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "nonlinear_response";
  out.status = r.status;
  out.message = r.message;
  out.tables = {response_table(r), harmonics_table(r), energy_table(r),
                turning_table(r),  branch_table(r),    loops_table(r)};
  out.plots = plots(r);
  out.notes = notes(r);
  return out;
}

}  // namespace geardyn::analyses
