// Waterfall (short-time spectra vs speed) of synthetic records: a linear run-up chirp with known
// orders, whose block maxima must lie on the order lines f = o n / 60, and a stationary sine,
// which must read its amplitude after the window's coherent-gain correction.
// References: J. B. Allen, "Short term spectral analysis, synthesis, and modification by
// discrete Fourier transform", IEEE Trans. Acoust. Speech Signal Process. 25 (1977) 235-238;
// F. J. Harris, "On the use of windows for harmonic analysis with the discrete Fourier
// transform", Proc. IEEE 66 (1978) 51-83 (coherent gain, scalloping loss).
#include "geardyn/signal/waterfall.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace geardyn::signal {
namespace {

constexpr double kPi = std::numbers::pi;

// Linear run-up n(t) = n0 + a t [rev/s] from 600 to 2400 rpm in 10 s.
constexpr double kN0 = 10.0;
constexpr double kAcc = 3.0;
constexpr double kFs = 16384.0;

struct Record {
  Eigen::VectorXd t, x, angle, speed_rpm;
};

Record chirp(double duration) {
  const auto n = static_cast<Eigen::Index>(duration * kFs);
  Record r{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index j = 0; j < n; ++j) {
    const double t = static_cast<double>(j) / kFs;
    r.t[j] = t;
    r.angle[j] = 2 * kPi * (kN0 * t + 0.5 * kAcc * t * t);
    r.speed_rpm[j] = 60.0 * (kN0 + kAcc * t);
    // Orders 13 (amplitude 1) and 26 (amplitude 0.5) of the shaft.
    r.x[j] = std::cos(13.0 * r.angle[j]) + 0.5 * std::cos(26.0 * r.angle[j] + 0.7);
  }
  return r;
}

Eigen::Index argmax(const Eigen::VectorXd& v, Eigen::Index from, Eigen::Index to) {
  Eigen::Index best = from;
  for (Eigen::Index k = from; k < to; ++k)
    if (v[k] > v[best]) best = k;
  return best;
}

TEST(Waterfall, RunUpBlockMaximaLieOnTheOrderLines) {
  const Record r = chirp(10.0);
  WaterfallOptions o;
  o.block_length = 4096;  // 0.25 s, 4 Hz bins; order 26 sweeps 19.5 Hz (5 bins) per block
  o.overlap = 0.5;
  const Waterfall w = waterfall_by_angle(r.t, r.x, r.angle, o);
  ASSERT_EQ(w.amplitude.rows(), (r.t.size() - 4096) / 2048 + 1);
  EXPECT_DOUBLE_EQ(w.resolution_hz, 4.0);
  for (Eigen::Index b = 0; b < w.amplitude.rows(); ++b) {
    // Mean speed from the angle record is exact for any profile: for a linear ramp it is the
    // speed at the block's mid time (up to the half-sample offset of the last sample).
    EXPECT_NEAR(w.speed_rpm[b], 60.0 * (kN0 + kAcc * w.time_s[b]), 1e-9 * w.speed_rpm[b]);
    const Eigen::VectorXd a = w.amplitude.row(b).transpose();
    const double f13 = order_line_hz(13.0, w.speed_rpm.segment(b, 1))[0];
    const double f26 = order_line_hz(26.0, w.speed_rpm.segment(b, 1))[0];
    // The largest bin of the block is on order 13's line, within one bin; the largest above
    // 1.5 f13 on order 26's line. A linear chirp's Hann-windowed spectrum is symmetric about its
    // mid frequency, so the peak bin is the one nearest o n_mean / 60.
    const Eigen::Index k13 = argmax(a, 1, a.size());
    const auto from = static_cast<Eigen::Index>(1.5 * f13 / w.resolution_hz);
    const Eigen::Index k26 = argmax(a, from, a.size());
    EXPECT_LE(std::abs(w.frequency_hz[k13] - f13), w.resolution_hz) << "block " << b;
    EXPECT_LE(std::abs(w.frequency_hz[k26] - f26), w.resolution_hz) << "block " << b;
  }
}

TEST(Waterfall, SpeedRecordGivesTheSameBlockSpeeds) {
  const Record r = chirp(2.0);
  WaterfallOptions o;
  o.block_length = 2048;
  o.overlap = 0.0;
  const Waterfall a = waterfall_by_angle(r.t, r.x, r.angle, o);
  const Waterfall s = waterfall_by_speed(r.t, r.x, r.speed_rpm, o);
  ASSERT_EQ(a.speed_rpm.size(), s.speed_rpm.size());
  // The mean of a linear ramp's samples is its mid value: both agree to rounding.
  for (Eigen::Index b = 0; b < a.speed_rpm.size(); ++b)
    EXPECT_NEAR(a.speed_rpm[b], s.speed_rpm[b], 1e-9 * a.speed_rpm[b]);
  EXPECT_EQ((a.amplitude - s.amplitude).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Waterfall, StationarySineReadsItsAmplitude) {
  // 1500 rpm, order 13 = 325 Hz. fs / L = 4 Hz: 325 Hz is between bins 81 and 82 (a quarter bin
  // off), where Hann loses up to 15 % (Harris 1978) and the flat top less than 0.1 %.
  const auto n = static_cast<Eigen::Index>(2 * kFs);
  Eigen::VectorXd t(n), x(n), speed(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    t[j] = static_cast<double>(j) / kFs;
    x[j] = 2.5 * std::sin(2 * kPi * 325.0 * t[j]);
    speed[j] = 1500.0;
  }
  WaterfallOptions o;
  o.block_length = 4096;
  o.window = Window::FlatTop;
  const Waterfall w = waterfall_by_speed(t, x, speed, o);
  for (Eigen::Index b = 0; b < w.amplitude.rows(); ++b) {
    EXPECT_NEAR(w.amplitude.row(b).maxCoeff() / 2.5, 1.0, max_scalloping_loss(Window::FlatTop));
    EXPECT_DOUBLE_EQ(w.speed_rpm[b], 1500.0);
  }
  // On a bin (324 Hz = bin 81) every window reads the amplitude to rounding.
  for (Eigen::Index j = 0; j < n; ++j) x[j] = 2.5 * std::sin(2 * kPi * 324.0 * t[j]);
  for (Window win : {Window::Rectangular, Window::Hann, Window::FlatTop}) {
    o.window = win;
    const Waterfall on = waterfall_by_speed(t, x, speed, o);
    for (Eigen::Index b = 0; b < on.amplitude.rows(); ++b)
      EXPECT_NEAR(on.amplitude(b, 81), 2.5, 1e-9) << to_string(win);
  }
}

TEST(Waterfall, BadInputsThrowNamingTheSample) {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(100, 0.0, 0.99);
  const Eigen::VectorXd x = Eigen::VectorXd::Zero(100);
  WaterfallOptions o;
  o.block_length = 200;
  EXPECT_THROW(waterfall_by_speed(t, x, x, o), std::invalid_argument);  // shorter than a block
  o.block_length = 32;
  o.overlap = 1.0;
  EXPECT_THROW(waterfall_by_speed(t, x, x, o), std::invalid_argument);
  o.overlap = 0.5;
  t[50] = t[49];
  try {
    waterfall_by_speed(t, x, x, o);
    FAIL() << "non-increasing time accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 50"), std::string::npos) << e.what();
  }
  EXPECT_THROW(uniform_sample_rate(Eigen::VectorXd::LinSpaced(1, 0.0, 0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
