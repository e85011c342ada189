#include "geardyn/drivetrain/drivers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geardyn::drivetrain {

PiecewiseLinear::PiecewiseLinear(std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)) {
  if (x_.empty() || x_.size() != y_.size())
    throw std::invalid_argument("PiecewiseLinear: x and y of equal, non-zero length");
  for (std::size_t k = 1; k < x_.size(); ++k)
    if (!(x_[k] > x_[k - 1])) throw std::invalid_argument("PiecewiseLinear: x not increasing");
  cumulative_.assign(x_.size(), 0.0);
  for (std::size_t k = 1; k < x_.size(); ++k)
    cumulative_[k] = cumulative_[k - 1] + 0.5 * (y_[k] + y_[k - 1]) * (x_[k] - x_[k - 1]);
}

double PiecewiseLinear::value(double x, double* slope) const {
  if (slope != nullptr) *slope = 0.0;
  if (x_.empty()) return 0.0;
  if (x < x_.front() || x_.size() == 1) return y_.front();
  if (x >= x_.back()) return y_.back();
  // At a node the slope is the right-hand one (a speed ramp starting at t_0 accelerates at t_0).
  const auto k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
  const double s = (y_[k] - y_[k - 1]) / (x_[k] - x_[k - 1]);
  if (slope != nullptr) *slope = s;
  return y_[k - 1] + s * (x - x_[k - 1]);
}

double PiecewiseLinear::integral(double x) const {
  if (x_.empty()) return 0.0;
  if (x <= x_.front()) return y_.front() * (x - x_.front());
  if (x >= x_.back()) return cumulative_.back() + y_.back() * (x - x_.back());
  const auto k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
  return cumulative_[k - 1] + 0.5 * (y_[k - 1] + value(x)) * (x - x_[k - 1]);
}

double SpeedDriver::acceleration(double t) const {
  double slope = 0.0;
  speed.value(t, &slope);
  return slope;
}

double LoadTorque::value(double t, double omega, double* d_omega) const {
  double slope = 0.0;
  double T = torque - drag * omega * std::abs(omega);
  double dT = -2.0 * drag * std::abs(omega);
  if (!table.empty()) {
    T += table.value(table_over_time ? t : omega, &slope);
    if (!table_over_time) dT += slope;
  }
  if (d_omega != nullptr) *d_omega = dT;
  return T;
}

ClutchElement::ClutchElement(std::string name, double max_torque, double slip_speed,
                             double engage_time)
    : name_(std::move(name)),
      max_torque_(max_torque),
      slip_speed_(slip_speed),
      engage_time_(engage_time) {
  if (!(max_torque_ >= 0.0) || !(slip_speed_ > 0.0) || !std::isfinite(engage_time_))
    throw std::invalid_argument("ClutchElement: max_torque >= 0, slip_speed > 0, finite time");
}

void ClutchElement::evaluate(const Eigen::VectorXd& /*u*/, const Eigen::VectorXd& v, double t,
                             elements::ElementForce& out) const {
  out.reset(1);
  if (t < engage_time_) return;
  const double x = v[0] / slip_speed_;
  const double th = std::tanh(x);
  out.force[0] = max_torque_ * th;
  out.damping(0, 0) = max_torque_ * (1.0 - th * th) / slip_speed_;
}

}  // namespace geardyn::drivetrain
