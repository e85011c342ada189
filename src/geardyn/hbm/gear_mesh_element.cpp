#include "geardyn/hbm/gear_mesh_element.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::hbm {

namespace {

// The segment [i0, i0 + 1] of an N-point periodic grid containing theta, and the weight w of
// its end node.
struct Segment {
  std::size_t i0 = 0, i1 = 0;
  double w = 0.0;
};

Segment locate(std::size_t n, double theta) {
  const double x = theta / units::kTwoPi * static_cast<double>(n);
  const double fl = std::floor(x);
  double i = std::fmod(fl, static_cast<double>(n));
  if (i < 0.0) i += static_cast<double>(n);
  Segment s;
  s.i0 = static_cast<std::size_t>(i) % n;
  s.i1 = (s.i0 + 1) % n;
  s.w = x - fl;
  return s;
}

void check_table(const MeshCycleTable& table, const std::string& key, bool positive) {
  if (table.values.empty()) throw InputError({}, key, "at least one value", "an empty table");
  for (std::size_t i = 0; i < table.values.size(); ++i) {
    const double v = table.values[i];
    if (!std::isfinite(v) || (positive && v <= 0.0))
      throw InputError({}, fmt::format("{}[{}]", key, i),
                       positive ? "a finite value > 0" : "a finite value", fmt::format("{}", v));
  }
}

// The flank in contact for the drive-flank penetration p = delta - e and the backlash b.
elements::MeshContactState contact(double p, double b) {
  if (p > 0.0) return elements::MeshContactState::drive;
  if (-p - b > 0.0) return elements::MeshContactState::back;
  return elements::MeshContactState::separated;
}

}  // namespace

double MeshCycleTable::value(double theta) const {
  const std::size_t n = values.size();
  if (n == 1) return values[0];
  const Segment s = locate(n, theta);
  return (1.0 - s.w) * values[s.i0] + s.w * values[s.i1];
}

double MeshCycleTable::slope(double theta) const {
  const std::size_t n = values.size();
  if (n == 1) return 0.0;
  const Segment s = locate(n, theta);
  return (values[s.i1] - values[s.i0]) * static_cast<double>(n) / units::kTwoPi;
}

GearMeshBacklash::GearMeshBacklash(std::string name, GearMeshBacklashParameters parameters)
    : name_(std::move(name)), parameters_(std::move(parameters)) {
  check_table(parameters_.stiffness, name_ + ".stiffness", true);
  check_table(parameters_.unloaded_te, name_ + ".unloaded_te", false);
  const double b = parameters_.backlash, c = parameters_.damping;
  if (std::isnan(b) || b < 0.0)
    throw InputError({}, name_ + ".backlash", "a backlash >= 0 [m] (or infinite: no back flank)",
                     fmt::format("{}", b));
  if (!std::isfinite(c) || c < 0.0)
    throw InputError({}, name_ + ".damping", "a finite damping >= 0 [N s/m]", fmt::format("{}", c));
}

std::string GearMeshBacklash::describe() const { return fmt::format("gear mesh '{}'", name_); }

elements::MeshContactState GearMeshBacklash::state(double delta, double theta) const {
  return contact(delta - parameters_.unloaded_te.value(theta), parameters_.backlash);
}

void GearMeshBacklash::pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta,
                                 double omega, ElementStep& out) const {
  if (!std::isfinite(u[0]) || !std::isfinite(v[0]))
    throw NumericalError(describe(), fmt::format("a non-finite approach ({}) or rate ({}) at "
                                                 "phase {:.4g} rad",
                                                 u[0], v[0], theta));
  const double p = u[0] - parameters_.unloaded_te.value(theta);
  const elements::MeshContactState s = contact(p, parameters_.backlash);
  if (s == elements::MeshContactState::separated) return;
  const double k = parameters_.stiffness.value(theta), c = parameters_.damping;
  const double rate = v[0] - omega * parameters_.unloaded_te.slope(theta);
  // Drive: k p + c p'; back: -(k p_b + c p_b') = k (p + b) + c p'.
  const double elastic = s == elements::MeshContactState::drive ? p : p + parameters_.backlash;
  out.force[0] = k * elastic + c * rate;
  out.stiffness(0, 0) = k;
  out.damping(0, 0) = c;
}

void GearMeshBacklash::pointwise_omega_derivative(const Eigen::VectorXd& u,
                                                  const Eigen::VectorXd& /*v*/, double theta,
                                                  double /*omega*/, Eigen::VectorXd& out) const {
  if (parameters_.damping == 0.0) return;
  if (state(u[0], theta) == elements::MeshContactState::separated) return;
  out[0] = -parameters_.damping * parameters_.unloaded_te.slope(theta);
}

ElementLoop GearMeshBacklash::loop(const HarmonicBasis& basis, const Eigen::VectorXd& w,
                                   double omega) const {
  ElementLoop r = PointwiseElement::loop(basis, w, omega);
  const int n = basis.time_samples();
  int open = 0, back = 0;
  for (int j = 0; j < n; ++j) {
    const elements::MeshContactState s = state(r.displacement(j, 0), units::kTwoPi * j / n);
    if (s == elements::MeshContactState::separated) ++open;
    if (s == elements::MeshContactState::back) ++back;
  }
  r.open_fraction = static_cast<double>(open) / n;
  r.slip_fraction = static_cast<double>(back) / n;
  r.stick_fraction = std::numeric_limits<double>::quiet_NaN();
  return r;
}

}  // namespace geardyn::hbm
