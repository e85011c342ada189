#include "geardyn/signal/order_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/core/units.hpp"
#include "geardyn/signal/spectrum.hpp"

namespace geardyn::signal {
namespace {

void check_increasing(const Eigen::Ref<const Eigen::VectorXd>& v, const std::string& what) {
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    if (!std::isfinite(v[j]))
      throw std::invalid_argument(what + " is not finite at sample " + std::to_string(j));
    if (j > 0 && !(v[j] > v[j - 1]))
      throw std::invalid_argument(what + " is not strictly increasing at sample " +
                                  std::to_string(j) + " (" + std::to_string(v[j]) + " after " +
                                  std::to_string(v[j - 1]) + ")");
  }
}

void check_same_size(Eigen::Index a, Eigen::Index b, const std::string& what) {
  if (a != b)
    throw std::invalid_argument(what + ": " + std::to_string(a) + " times but " +
                                std::to_string(b) + " values");
}

// Slopes of the monotone cubic Hermite interpolant through (knot_i, value_i): the derivative of
// the parabola through three neighbouring points, limited to [0, 3 min(secants)] (Fritsch &
// Carlson 1980), so the curve stays increasing for increasing data.
Eigen::VectorXd hermite_slopes(const Eigen::VectorXd& knot, const Eigen::VectorXd& value) {
  const Eigen::Index m = knot.size();
  Eigen::VectorXd h = knot.tail(m - 1) - knot.head(m - 1);
  Eigen::VectorXd delta = (value.tail(m - 1) - value.head(m - 1)).cwiseQuotient(h);
  Eigen::VectorXd d(m);
  if (m == 2) {
    d.setConstant(delta[0]);
    return d;
  }
  for (Eigen::Index i = 1; i + 1 < m; ++i) {
    const double slope = (h[i - 1] * delta[i] + h[i] * delta[i - 1]) / (h[i - 1] + h[i]);
    d[i] = std::clamp(slope, 0.0, 3.0 * std::min(delta[i - 1], delta[i]));
  }
  const Eigen::Index e = m - 2;
  const double first = ((2 * h[0] + h[1]) * delta[0] - h[0] * delta[1]) / (h[0] + h[1]);
  const double last = ((2 * h[e] + h[e - 1]) * delta[e] - h[e] * delta[e - 1]) / (h[e] + h[e - 1]);
  d[0] = std::clamp(first, 0.0, 3.0 * delta[0]);
  d[m - 1] = std::clamp(last, 0.0, 3.0 * delta[e]);
  return d;
}

// Four-point Lagrange interpolation of x at time t inside interval [j, j+1] (points j-1 .. j+2,
// shifted at the ends of the record).
double lagrange4(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                 const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index j, double t) {
  const Eigen::Index n = time_s.size();
  const Eigen::Index s = std::clamp<Eigen::Index>(j - 1, 0, n - 4);
  double sum = 0.0;
  for (Eigen::Index a = s; a < s + 4; ++a) {
    double basis = 1.0;
    for (Eigen::Index b = s; b < s + 4; ++b)
      if (b != a) basis *= (t - time_s[b]) / (time_s[a] - time_s[b]);
    sum += basis * x[a];
  }
  return sum;
}

struct Blocks {
  int length = 0;
  int step = 0;
  int count = 0;
};

Blocks make_blocks(const AngleDomainRecord& record, int revolutions, double overlap,
                   const char* who) {
  if (revolutions < 1)
    throw std::invalid_argument(std::string(who) + ": revolutions per block must be at least 1");
  if (!(overlap >= 0.0 && overlap < 1.0))
    throw std::invalid_argument(std::string(who) + ": overlap must be in [0, 1), got " +
                                std::to_string(overlap));
  Blocks b;
  b.length = revolutions * record.samples_per_revolution;
  b.step = std::max(1, b.length - static_cast<int>(std::lround(overlap * b.length)));
  const auto n = static_cast<int>(record.value.size());
  if (b.length < 2 || n < b.length)
    throw std::invalid_argument(std::string(who) + ": the record covers " +
                                std::to_string(n / std::max(1, record.samples_per_revolution)) +
                                " revolutions, fewer than one block of " +
                                std::to_string(revolutions));
  b.count = (n - b.length) / b.step + 1;
  return b;
}

// Mean speed [rpm] and mid time of the block starting at `start`.
void block_speed(const AngleDomainRecord& r, int start, int length, double& rpm, double& mid) {
  const double t0 = r.time_s[start];
  const double t1 = r.time_s[start + length - 1];
  const double revolutions = static_cast<double>(length - 1) / r.samples_per_revolution;
  rpm = 60.0 * revolutions / (t1 - t0);
  mid = 0.5 * (t0 + t1);
}

}  // namespace

Eigen::VectorXd tacho_pulse_times(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                  const Eigen::Ref<const Eigen::VectorXd>& tacho,
                                  double threshold) {
  check_same_size(time_s.size(), tacho.size(), "tacho");
  check_increasing(time_s, "time");
  std::vector<double> pulses;
  for (Eigen::Index j = 1; j < tacho.size(); ++j) {
    if (tacho[j - 1] < threshold && tacho[j] >= threshold) {
      const double s = (threshold - tacho[j - 1]) / (tacho[j] - tacho[j - 1]);
      pulses.push_back(time_s[j - 1] + s * (time_s[j] - time_s[j - 1]));
    }
  }
  if (pulses.empty())
    throw std::invalid_argument("tacho: no pulses (the signal never rises through the threshold " +
                                std::to_string(threshold) + ")");
  return Eigen::Map<const Eigen::VectorXd>(pulses.data(), static_cast<Eigen::Index>(pulses.size()));
}

Eigen::VectorXd angle_from_pulse_times(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                       const Eigen::Ref<const Eigen::VectorXd>& pulse_times_s,
                                       int pulses_per_revolution) {
  if (pulses_per_revolution < 1)
    throw std::invalid_argument("tacho: pulses per revolution must be at least 1, got " +
                                std::to_string(pulses_per_revolution));
  if (pulse_times_s.size() < 2)
    throw std::invalid_argument("tacho: " + std::to_string(pulse_times_s.size()) +
                                " pulses, at least 2 are needed to define a speed");
  check_increasing(pulse_times_s, "tacho pulse time");
  check_increasing(time_s, "time");
  const Eigen::Index m = pulse_times_s.size();
  const Eigen::VectorXd knot = pulse_times_s;
  Eigen::VectorXd value(m);
  for (Eigen::Index i = 0; i < m; ++i)
    value[i] = units::kTwoPi * static_cast<double>(i) / pulses_per_revolution;
  const Eigen::VectorXd d = hermite_slopes(knot, value);

  Eigen::VectorXd angle(time_s.size());
  Eigen::Index i = 0;
  for (Eigen::Index j = 0; j < time_s.size(); ++j) {
    const double t = time_s[j];
    while (i + 2 < m && t > knot[i + 1]) ++i;  // t increases: sweep the interval forward
    const double h = knot[i + 1] - knot[i];
    const double s = (t - knot[i]) / h;
    const double s2 = s * s;
    const double s3 = s2 * s;
    angle[j] = (2 * s3 - 3 * s2 + 1) * value[i] + (s3 - 2 * s2 + s) * h * d[i] +
               (-2 * s3 + 3 * s2) * value[i + 1] + (s3 - s2) * h * d[i + 1];
  }
  return angle;
}

AngleDomainRecord resample_to_angle(const Eigen::Ref<const Eigen::VectorXd>& time_s,
                                    const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const Eigen::Ref<const Eigen::VectorXd>& angle_rad,
                                    int samples_per_revolution) {
  check_same_size(time_s.size(), x.size(), "order tracking: signal");
  check_same_size(time_s.size(), angle_rad.size(), "order tracking: angle");
  if (samples_per_revolution < 4)
    throw std::invalid_argument("order tracking: samples per revolution must be at least 4, got " +
                                std::to_string(samples_per_revolution));
  if (time_s.size() < 4)
    throw std::invalid_argument("order tracking: the record has fewer than 4 samples");
  check_increasing(time_s, "time");
  check_increasing(angle_rad, "shaft angle");
  if (!x.allFinite())
    throw std::invalid_argument("order tracking: the signal has non-finite samples");

  const double step = units::kTwoPi / samples_per_revolution;
  const Eigen::Index n = time_s.size();
  const double theta0 = angle_rad[0];
  const auto count =
      static_cast<Eigen::Index>(std::floor((angle_rad[n - 1] - theta0) / step * (1 + 1e-14))) + 1;

  AngleDomainRecord r;
  r.samples_per_revolution = samples_per_revolution;
  r.angle_rad.resize(count);
  r.time_s.resize(count);
  r.value.resize(count);
  Eigen::Index j = 0;
  for (Eigen::Index k = 0; k < count; ++k) {
    const double phi = std::min(theta0 + static_cast<double>(k) * step, angle_rad[n - 1]);
    while (j + 2 < n && angle_rad[j + 1] < phi) ++j;
    const double s = (phi - angle_rad[j]) / (angle_rad[j + 1] - angle_rad[j]);
    const double t = time_s[j] + s * (time_s[j + 1] - time_s[j]);
    r.angle_rad[k] = theta0 + static_cast<double>(k) * step;
    r.time_s[k] = t;
    r.value[k] = lagrange4(time_s, x, j, t);
  }
  return r;
}

OrderSpectra order_spectra(const AngleDomainRecord& record, int revolutions_per_block,
                           Window window, double overlap) {
  const Blocks b = make_blocks(record, revolutions_per_block, overlap, "order spectra");
  OrderSpectra s;
  s.revolutions_per_block = revolutions_per_block;
  s.order = frequency_axis(b.length, static_cast<double>(record.samples_per_revolution));
  s.amplitude.resize(b.count, s.order.size());
  s.speed_rpm.resize(b.count);
  s.time_s.resize(b.count);
  for (int i = 0; i < b.count; ++i) {
    const int start = i * b.step;
    const AmplitudeSpectrum a =
        amplitude_spectrum(record.value.segment(start, b.length),
                           static_cast<double>(record.samples_per_revolution), window);
    s.amplitude.row(i) = a.amplitude.transpose();
    block_speed(record, start, b.length, s.speed_rpm[i], s.time_s[i]);
  }
  return s;
}

OrderCuts order_cuts(const AngleDomainRecord& record,
                     const Eigen::Ref<const Eigen::VectorXd>& orders, int revolutions_per_block,
                     Window window, double overlap) {
  const Blocks b = make_blocks(record, revolutions_per_block, overlap, "order cuts");
  const double nyquist = 0.5 * record.samples_per_revolution;
  for (Eigen::Index o = 0; o < orders.size(); ++o)
    if (!(orders[o] >= 0.0 && orders[o] < nyquist))
      throw std::invalid_argument("order cuts: order " + std::to_string(orders[o]) +
                                  " is outside [0, " + std::to_string(nyquist) + ") for " +
                                  std::to_string(record.samples_per_revolution) +
                                  " samples per revolution");
  const Eigen::VectorXd w = window_coefficients(window, b.length);
  const double sum_w = w.sum();
  OrderCuts c;
  c.order = orders;
  c.amplitude.resize(b.count, orders.size());
  c.speed_rpm.resize(b.count);
  c.time_s.resize(b.count);
  const double step = units::kTwoPi / record.samples_per_revolution;
  for (int i = 0; i < b.count; ++i) {
    const int start = i * b.step;
    for (Eigen::Index o = 0; o < orders.size(); ++o) {
      std::complex<double> sum = 0.0;
      for (int j = 0; j < b.length; ++j)
        sum += w[j] * record.value[start + j] * std::polar(1.0, -orders[o] * step * j);
      c.amplitude(i, o) = (orders[o] == 0.0 ? 1.0 : 2.0) * std::abs(sum) / sum_w;
    }
    block_speed(record, start, b.length, c.speed_rpm[i], c.time_s[i]);
  }
  return c;
}

}  // namespace geardyn::signal
