// Unit tests of signal/orbit against orbits traced in the time domain.
#include "geardyn/signal/orbit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace geardyn::signal {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// Semi-axes, inclination and turning sense of x = Re(X e^{it}), y = Re(Y e^{it}) by sampling
// one period densely: the independent oracle for orbit_from_phasors.
struct Traced {
  double major = 0, minor = 1e300, inclination = 0;
  double signed_area = 0;  // > 0: counter-clockwise (e1 towards e2)
};
Traced trace(Complex X, Complex Y) {
  Traced t;
  const int n = 200000;
  double px = std::real(X), py = std::real(Y);
  for (int k = 1; k <= n; ++k) {
    const Complex e = std::polar(1.0, 2.0 * kPi * k / n);
    const double x = std::real(X * e), y = std::real(Y * e);
    const double r = std::hypot(x, y);
    if (r > t.major) {
      t.major = r;
      t.inclination = std::atan2(y, x);
    }
    t.minor = std::min(t.minor, r);
    t.signed_area += 0.5 * (px * y - py * x);
    px = x;
    py = y;
  }
  t.inclination = std::remainder(t.inclination, kPi);
  return t;
}

TEST(Orbit, ForwardAndBackwardCircles) {
  // x = cos t, y = sin t turns from e1 towards e2: Y = -i X.
  const auto f = orbit_from_phasors(Complex(2.0, 0.0), Complex(0.0, -2.0));
  EXPECT_NEAR(f.major, 2.0, 1e-15);
  EXPECT_NEAR(f.minor, 2.0, 1e-15);
  EXPECT_EQ(f.whirl, Whirl::Forward);
  EXPECT_NEAR(f.backward_radius, 0.0, 1e-15);
  const auto b = orbit_from_phasors(Complex(2.0, 0.0), Complex(0.0, 2.0));
  EXPECT_EQ(b.whirl, Whirl::Backward);
  EXPECT_NEAR(b.forward_radius, 0.0, 1e-15);
}

TEST(Orbit, StraightLineAtFortyFiveDegrees) {
  const auto o = orbit_from_phasors(Complex(1.0, 1.0), Complex(1.0, 1.0));
  EXPECT_EQ(o.whirl, Whirl::Straight);
  EXPECT_NEAR(o.major, 2.0, 1e-15);  // |X| sqrt(2) = 2
  EXPECT_NEAR(o.minor, 0.0, 1e-15);
  EXPECT_NEAR(o.inclination, kPi / 4, 1e-15);
  EXPECT_EQ(orbit_from_phasors(Complex(0.0), Complex(0.0)).whirl, Whirl::Straight);
}

TEST(Orbit, GeneralEllipseMatchesTimeDomainTrace) {
  for (const auto& [X, Y] : {std::pair{Complex(1.0, 0.3), Complex(-0.4, 0.9)},
                             std::pair{Complex(-0.2, 0.7), Complex(0.5, 0.1)},
                             std::pair{Complex(0.0, -1.5), Complex(0.3, 0.2)}}) {
    const auto o = orbit_from_phasors(X, Y);
    const auto t = trace(X, Y);
    // The trace samples 2e5 points per period: its extremes are off by < (2 pi / 2e5)^2 / 2
    // relative, about 5e-10; its inclination by the angular step, 3e-5 rad.
    EXPECT_NEAR(o.major, t.major, 1e-8) << X << Y;
    EXPECT_NEAR(o.minor, t.minor, 1e-8) << X << Y;
    EXPECT_NEAR(std::remainder(o.inclination - t.inclination, kPi), 0.0, 1e-4) << X << Y;
    EXPECT_EQ(o.whirl, t.signed_area > 0 ? Whirl::Forward : Whirl::Backward) << X << Y;
    EXPECT_GT(o.inclination, -kPi / 2);
    EXPECT_LE(o.inclination, kPi / 2);
  }
}

TEST(Orbit, ReversedSwapsSense) {
  EXPECT_EQ(reversed(Whirl::Forward), Whirl::Backward);
  EXPECT_EQ(reversed(Whirl::Backward), Whirl::Forward);
  EXPECT_EQ(reversed(Whirl::Straight), Whirl::Straight);
  EXPECT_EQ(to_string(Whirl::Backward), "backward");
}

}  // namespace
}  // namespace geardyn::signal
