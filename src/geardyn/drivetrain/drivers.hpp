#pragma once
// What turns a drivetrain and what loads it (docs/theory.md §16.10), each acting on the spin
// rotation (rz, about the node frame's e3) of one node:
//   * a speed driver prescribes the angle theta(t) = theta_0 + integral of the speed table
//     (piecewise linear in time, held after its last point), so its speed and acceleration too;
//   * a motor applies T_m(omega), piecewise linear in speed (held outside the table), and adds
//     its rotor inertia to the node;
//   * a load torque applies T_0 + T_table(omega or t) - c_d omega |omega|;
//   * a clutch or brake transmits T = T_max tanh(slip / omega_eps) (regularised Coulomb
//     friction), zero before its engagement time: a ForceElement on the relative spin.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/elements/force_element.hpp"

namespace geardyn::drivetrain {

/// y(x) piecewise linear through (x_k, y_k), constant outside; x strictly increasing, >= 1 point.
/// The slope at a node is the right-hand one (0 at and after the last node).
class PiecewiseLinear {
 public:
  PiecewiseLinear() = default;
  PiecewiseLinear(std::vector<double> x, std::vector<double> y);
  double value(double x, double* slope = nullptr) const;
  /// integral_{x_0}^{x} y (x below x_0: y_0 (x - x_0)).
  double integral(double x) const;
  bool empty() const { return x_.empty(); }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }

 private:
  std::vector<double> x_, y_, cumulative_;
};

/// A prescribed spin: angle, speed and acceleration at time t.
struct SpeedDriver {
  std::string name;
  int equation = -1;      ///< the node's rz equation
  PiecewiseLinear speed;  ///< over time [rad/s]
  double angle0 = 0.0;    ///< theta at t = 0 [rad]
  double angle(double t) const { return angle0 + speed.integral(t); }
  double velocity(double t) const { return speed.value(t); }
  double acceleration(double t) const;
};

struct Motor {
  std::string name;
  int equation = -1;
  PiecewiseLinear torque;  ///< over speed [N m]
  double inertia = 0.0;    ///< [kg m^2]
};

struct LoadTorque {
  std::string name;
  int equation = -1;
  double torque = 0.0;
  PiecewiseLinear table;  ///< over speed or time (empty: none)
  bool table_over_time = false;
  double drag = 0.0;
  /// Torque at time t and speed omega, and d torque / d omega.
  double value(double t, double omega, double* d_omega) const;
};

/// Regularised Coulomb friction between two spins (or a spin and ground): n = 1, u the relative
/// angle, v the slip speed; force = T_max tanh(v / omega_eps) after the engagement time.
class ClutchElement final : public elements::ForceElement {
 public:
  ClutchElement(std::string name, double max_torque, double slip_speed, double engage_time);
  Eigen::Index size() const override { return 1; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                elements::ElementForce& out) const override;
  std::string describe() const override { return "clutch '" + name_ + "'"; }

 private:
  std::string name_;
  double max_torque_, slip_speed_, engage_time_;
};

}  // namespace geardyn::drivetrain
