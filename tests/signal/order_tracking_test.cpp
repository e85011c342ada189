// Computed order tracking: synthetic run-ups with a known speed profile and known order
// amplitudes (the validation of issue #17). In the angle domain a component a cos(o theta + phi)
// is a steady sinusoid of o cycles per revolution whatever the speed, so the order spectrum of a
// block of whole revolutions reads a exactly on its order bin (K. R. Fyfe, E. D. S. Munck,
// "Analysis of computed order tracking", Mech. Syst. Signal Process. 11 (1997) 187-205); what
// remains is the resampling error, bounded below.
#include "geardyn/signal/order_tracking.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;

// Linear run-up 600 -> 6000 rpm in 10 s: n(t) = n0 + a t [rev/s], theta = 2 pi (n0 t + a t^2/2).
constexpr double kN0 = 10.0;
constexpr double kAcc = 9.0;
constexpr double kDuration = 10.0;
constexpr double kFs = 16384.0;  // order 13 at 100 rev/s is 1300 Hz: 12.6 samples per cycle

constexpr std::array<double, 3> kOrders = {1.0, 2.5, 13.0};
constexpr std::array<double, 3> kAmplitudes = {1.0, 0.4, 0.15};
constexpr std::array<double, 3> kPhases = {0.3, -1.1, 2.0};

double theta(double t) { return 2 * kPi * (kN0 * t + 0.5 * kAcc * t * t); }

struct RunUp {
  Eigen::VectorXd t, x, angle;
};

RunUp run_up() {
  const auto n = static_cast<Eigen::Index>(kDuration * kFs) + 1;
  RunUp r{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index j = 0; j < n; ++j) {
    r.t[j] = static_cast<double>(j) / kFs;
    r.angle[j] = theta(r.t[j]);
    double x = 0.0;
    for (std::size_t o = 0; o < kOrders.size(); ++o)
      x += kAmplitudes[o] * std::cos(kOrders[o] * r.angle[j] + kPhases[o]);
    r.x[j] = x;
  }
  return r;
}

// Exact mean speed [rpm] over the block from its first to its last sample: the revolutions
// between them over the time the profile needs for them (t of an angle by the quadratic).
double exact_block_rpm(double rev0, double rev1) {
  auto time_of = [](double rev) { return (-kN0 + std::sqrt(kN0 * kN0 + 2 * kAcc * rev)) / kAcc; };
  return 60.0 * (rev1 - rev0) / (time_of(rev1) - time_of(rev0));
}

// Four-point Lagrange interpolation of a sinusoid with omega h = 2 pi / 12.6 (order 13 at the top
// speed) loses at most (omega h)^4 * 0.5625 / 24 = 1.5e-3 of its amplitude (the cubic's error
// term at mid-interval); the orders fall on bins of the 4-revolution blocks, so leakage between
// them is zero. Tolerance 2e-3, five times tighter than the 1 %.
void expect_orders_recovered(const AngleDomainRecord& record, double tolerance) {
  const int revs = 4;  // order resolution 0.25: orders 1, 2.5 and 13 fall on bins
  const Eigen::VectorXd orders = Eigen::Map<const Eigen::VectorXd>(kOrders.data(), 3);
  const OrderCuts cuts = order_cuts(record, orders, revs);
  const OrderSpectra spectra = order_spectra(record, revs);
  ASSERT_GT(cuts.amplitude.rows(), 100);  // 550 revolutions in 4-revolution blocks
  ASSERT_EQ(spectra.amplitude.rows(), cuts.amplitude.rows());
  // Away from the ends: the first and last block (the four-point stencil shifts there).
  for (Eigen::Index b = 1; b + 1 < cuts.amplitude.rows(); ++b) {
    for (std::size_t o = 0; o < kOrders.size(); ++o) {
      EXPECT_NEAR(cuts.amplitude(b, static_cast<Eigen::Index>(o)) / kAmplitudes[o], 1.0, tolerance)
          << "block " << b << " order " << kOrders[o];
      const auto bin = static_cast<Eigen::Index>(std::lround(kOrders[o] * revs));
      EXPECT_DOUBLE_EQ(spectra.order[bin], kOrders[o]);
      EXPECT_NEAR(spectra.amplitude(b, bin) / kAmplitudes[o], 1.0, tolerance);
    }
  }
}

TEST(OrderTracking, RunUpFromTheAngleChannelRecoversEachOrderAmplitude) {
  const RunUp r = run_up();
  const AngleDomainRecord record = resample_to_angle(r.t, r.x, r.angle, 64);
  expect_orders_recovered(record, 2e-3);
  // The speed of each block: the exact mean of the linear profile over the block, to 1e-6
  // (the time of each angle step comes from linear inversion of theta(t) between samples
  // 61 us apart: angle error below alpha h^2 / 8 = 1.5e-9 rad).
  const OrderCuts cuts = order_cuts(record, Eigen::VectorXd::Constant(1, 1.0), 4);
  for (Eigen::Index b = 0; b < cuts.speed_rpm.size(); ++b) {
    const double rev0 = 4.0 * static_cast<double>(b);
    const double rev1 = rev0 + 255.0 / 64.0;
    EXPECT_NEAR(cuts.speed_rpm[b] / exact_block_rpm(rev0, rev1), 1.0, 1e-6) << b;
  }
  EXPECT_GT(cuts.speed_rpm[cuts.speed_rpm.size() - 1], 5900.0);
}

TEST(OrderTracking, RunUpFromATachoColumnRecoversEachOrderAmplitude) {
  // A 16-pulse tacho (sin(16 theta - 0.5), rising zero crossings: 1600 Hz at the top speed,
  // 10 samples per pulse); the angle between pulses by the monotone cubic, exact for the constant
  // acceleration of this profile.
  const RunUp r = run_up();
  Eigen::VectorXd tacho(r.t.size());
  for (Eigen::Index j = 0; j < tacho.size(); ++j) tacho[j] = std::sin(16.0 * r.angle[j] - 0.5);
  const Eigen::VectorXd pulses = tacho_pulse_times(r.t, tacho, 0.0);
  ASSERT_EQ(pulses.size(), 16 * 550);
  const Eigen::VectorXd angle = angle_from_pulse_times(r.t, pulses, 16);
  // The angle from the pulses equals theta minus the first pulse's angle 0.5/16 rad between the
  // pulses. The pulse times come from linear interpolation of the tacho's zero crossings: for a
  // sine with samples at phases -a and D - a the crossing's phase error is a (D - a)(D - 2a)/6 to
  // third order, at most D^3/(36 sqrt 3) = 0.016 D^3. At the top speed D = 2 pi 1600/16384 =
  // 0.61 rad: 3.7e-3 rad of tacho phase, 2.3e-4 rad of shaft angle; bound 3e-4. (Order 13 sees
  // 3e-3 rad of phase jitter: an amplitude effect below 1e-5.)
  double max_error = 0.0;
  for (Eigen::Index j = 0; j < r.t.size(); ++j)
    if (r.t[j] > pulses[0] && r.t[j] < pulses[pulses.size() - 1])
      max_error = std::max(max_error, std::abs(angle[j] - (r.angle[j] - 0.5 / 16.0)));
  EXPECT_LT(max_error, 3e-4);
  // Keep to the part covered by the pulses.
  Eigen::Index first = 0;
  while (r.t[first] < pulses[0]) ++first;
  Eigen::Index last = r.t.size() - 1;
  while (r.t[last] > pulses[pulses.size() - 1]) --last;
  const Eigen::Index n = last - first + 1;
  const AngleDomainRecord record =
      resample_to_angle(r.t.segment(first, n), r.x.segment(first, n), angle.segment(first, n), 64);
  expect_orders_recovered(record, 2e-3);
}

TEST(OrderTracking, OncePerRevolutionPulsesGiveTheExactAngleOfAConstantAcceleration) {
  // Pulse times of a once-per-revolution tacho from the profile itself (t of each whole
  // revolution, exact). The cubic's slopes are the derivatives of the parabola through three
  // pulses, and theta(t) is a parabola: the interpolated angle is exact to rounding, and the
  // Fritsch-Carlson limit (slope <= 3 secants) is not active at this acceleration. 1e-9 rad
  // covers the rounding of angles up to 3500 rad.
  const RunUp r = run_up();
  Eigen::VectorXd pulses(550);
  for (Eigen::Index i = 0; i < pulses.size(); ++i) {
    const double rev = static_cast<double>(i);
    pulses[i] = (-kN0 + std::sqrt(kN0 * kN0 + 2 * kAcc * rev)) / kAcc;
  }
  const Eigen::VectorXd angle = angle_from_pulse_times(r.t, pulses, 1);
  double max_error = 0.0;
  for (Eigen::Index j = 0; j < r.t.size(); ++j)
    if (r.t[j] <= pulses[pulses.size() - 1])
      max_error = std::max(max_error, std::abs(angle[j] - r.angle[j]));
  EXPECT_LT(max_error, 1e-9);
}

TEST(OrderTracking, StationarySineReadsItsAmplitude) {
  // 1500 rpm, x = 2.3 cos(3 theta + 0.2): order 3 reads 2.3 in every block, the other order
  // bins near zero. On-bin and resampled from 4096 Hz (82 samples per cycle of order 3):
  // interpolation error below 1e-5.
  const double fs = 4096.0;
  const double speed = 25.0;  // rev/s
  Eigen::VectorXd t(8 * 4096), x(8 * 4096), angle(8 * 4096);
  for (Eigen::Index j = 0; j < t.size(); ++j) {
    t[j] = static_cast<double>(j) / fs;
    angle[j] = 2 * kPi * speed * t[j];
    x[j] = 2.3 * std::cos(3.0 * angle[j] + 0.2);
  }
  const AngleDomainRecord record = resample_to_angle(t, x, angle, 32);
  const OrderSpectra s = order_spectra(record, 8, Window::Hann, 0.5);
  ASSERT_GT(s.amplitude.rows(), 40);
  for (Eigen::Index b = 0; b < s.amplitude.rows(); ++b) {
    EXPECT_NEAR(s.amplitude(b, 24), 2.3, 2.3e-5);
    EXPECT_NEAR(s.amplitude(b, 40), 0.0, 1e-5);
    EXPECT_NEAR(s.speed_rpm[b], 1500.0, 1e-6);
  }
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

TEST(OrderTracking, BadInputGivesClearErrors) {
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(100, 0.0, 1.0);
  const Eigen::VectorXd flat = Eigen::VectorXd::Zero(100);
  EXPECT_NE(message_of([&] { tacho_pulse_times(t, flat, 0.5); }).find("no pulses"),
            std::string::npos);
  Eigen::VectorXd bad_t = t;
  bad_t[40] = bad_t[39];
  EXPECT_NE(message_of([&] {
              resample_to_angle(bad_t, flat, t, 16);
            }).find("time is not strictly increasing at sample 40"),
            std::string::npos);
  Eigen::VectorXd bad_angle = t * 100.0;
  bad_angle[70] = bad_angle[60];
  EXPECT_NE(message_of([&] {
              resample_to_angle(t, flat, bad_angle, 16);
            }).find("shaft angle is not strictly increasing at sample 70"),
            std::string::npos);
  EXPECT_THROW(angle_from_pulse_times(t, Eigen::VectorXd::Constant(1, 0.5), 1),
               std::invalid_argument);
  const AngleDomainRecord record = resample_to_angle(t, flat, t * 20.0, 16);  // 3.2 revolutions
  EXPECT_THROW(order_spectra(record, 4), std::invalid_argument);
  EXPECT_THROW(order_cuts(record, Eigen::VectorXd::Constant(1, 8.0), 1), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
