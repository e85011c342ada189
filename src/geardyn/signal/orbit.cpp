#include "geardyn/signal/orbit.hpp"

#include <cmath>

#include "geardyn/core/units.hpp"

namespace geardyn::signal {

Orbit orbit_from_phasors(std::complex<double> X, std::complex<double> Y) {
  constexpr std::complex<double> i(0.0, 1.0);
  const std::complex<double> forward = 0.5 * (X + i * Y);
  const std::complex<double> backward = 0.5 * (std::conj(X) + i * std::conj(Y));
  Orbit o;
  o.forward_radius = std::abs(forward);
  o.backward_radius = std::abs(backward);
  o.major = o.forward_radius + o.backward_radius;
  o.minor = std::abs(o.forward_radius - o.backward_radius);
  if (o.major == 0.0) return o;

  // |z| is largest when both circles point the same way: w t = (arg A_b - arg A_f) / 2, where
  // z points at (arg A_f + arg A_b) / 2. A vanishing circle has no phase: the orbit is then a
  // circle and the other circle's phase at t = 0 is taken (any direction is a major axis).
  double angle = 0.0;
  if (o.backward_radius == 0.0)
    angle = std::arg(forward);
  else if (o.forward_radius == 0.0)
    angle = std::arg(backward);
  else
    angle = 0.5 * (std::arg(forward) + std::arg(backward));
  angle = std::remainder(angle, units::kPi);  // in [-pi/2, pi/2]
  if (angle <= -0.5 * units::kPi) angle += units::kPi;
  o.inclination = angle;

  constexpr double kStraightTolerance = 1e-9;
  if (o.minor <= kStraightTolerance * o.major)
    o.whirl = Whirl::Straight;
  else
    o.whirl = o.forward_radius > o.backward_radius ? Whirl::Forward : Whirl::Backward;
  return o;
}

}  // namespace geardyn::signal
