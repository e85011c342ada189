#pragma once
// The Duffing oscillator of the issue "friction-hbm", shared by stability_test.cpp and
// duffing_time_test.cpp:
//
//   q'' + 0.05 q' + q + 0.1 q^3 = 0.18 cos(Omega t)     (m = 1, c = 0.05, k = 1, alpha = 0.1)
//
// its harmonic-balance system, the continuation of duffing_test.cpp (Omega 0.5 -> 2, arc step
// 0.005, residual 1e-12) and a classical fourth-order Runge-Kutta step of the equation of motion
// together with its variational equation Phi' = [[0, 1], [-(1 + 0.3 q^2), -0.05]] Phi.
#include <Eigen/Dense>
#include <cmath>
#include <utility>

#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm::testing {

inline constexpr double kMass = 1.0, kDamping = 0.05, kStiffness = 1.0, kCubic = 0.1, kForce = 0.18;

inline HarmonicBalance duffing_system(int harmonics) {
  const HarmonicBasis basis(harmonics, default_time_samples(harmonics, 3));
  const Eigen::VectorXd F =
      kForce * Eigen::VectorXd::Unit(basis.size(), HarmonicBasis::cos_index(1));
  return HarmonicBalance(
      Eigen::MatrixXd::Constant(1, 1, kMass), Eigen::MatrixXd::Constant(1, 1, kDamping),
      Eigen::MatrixXd::Constant(1, 1, kStiffness), basis, {cubic_spring(0, kCubic)}, F);
}

/// The response curve from Omega = 0.5 to 2 (through both folds), as in duffing_test.cpp.
inline ContinuationResult duffing_continuation(const HarmonicBalance& hb) {
  ContinuationOptions o;
  o.omega_start = 0.5;
  o.omega_end = 2.0;
  o.step = 0.005;
  o.max_step = 0.005;
  o.tolerance = 1e-12;
  const Eigen::VectorXd X0 =
      kForce / (kStiffness - 0.25) * Eigen::VectorXd::Unit(hb.size(), HarmonicBasis::cos_index(1));
  return continue_in_frequency(hb, X0, o);
}

/// Indices of the two points where Omega is extremal along the curve (the points nearest the
/// folds: the first is the largest Omega of the upper branch, the second the smallest Omega of
/// the middle branch). {-1, -1} when the curve does not turn twice.
inline std::pair<int, int> fold_points(const ContinuationResult& r) {
  int first = -1, second = -1;
  for (std::size_t i = 1; i + 1 < r.points.size(); ++i) {
    const double before = r.points[i].omega - r.points[i - 1].omega;
    const double after = r.points[i + 1].omega - r.points[i].omega;
    if (before * after < 0.0) {
      if (first < 0)
        first = static_cast<int>(i);
      else if (second < 0)
        second = static_cast<int>(i);
    }
  }
  return {first, second};
}

/// Newton on R(X, omega) = 0 at fixed omega from the guess X, to ||R|| <= 1e-13.
inline Eigen::VectorXd solve_at(const HarmonicBalance& hb, Eigen::VectorXd X, double omega) {
  Eigen::MatrixXd J;
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd R = hb.residual(X, omega, &J);
    if (R.norm() <= 1e-13) break;
    X -= J.partialPivLu().solve(R);
  }
  return X;
}

/// q(theta) and dq/dtheta of DOF 0 of the series X (layout of harmonic_basis.hpp).
inline std::pair<double, double> series_at(const Eigen::VectorXd& X, int harmonics, double theta) {
  double q = X[0], dq = 0.0;
  for (int n = 1; n <= harmonics; ++n) {
    const double a = X[HarmonicBasis::cos_index(n)], b = X[HarmonicBasis::sin_index(n)];
    q += a * std::cos(n * theta) + b * std::sin(n * theta);
    dq += n * (b * std::cos(n * theta) - a * std::sin(n * theta));
  }
  return {q, dq};
}

/// State of the equation of motion and, optionally, of its variational equation.
struct DuffingState {
  double q = 0.0, v = 0.0;
  Eigen::Matrix2d Phi = Eigen::Matrix2d::Identity();
};

inline DuffingState duffing_rate(double t, const DuffingState& s, double Omega, bool variational) {
  DuffingState r;
  r.q = s.v;
  r.v = (kForce * std::cos(Omega * t) - kDamping * s.v - kStiffness * s.q -
         kCubic * s.q * s.q * s.q) /
        kMass;
  if (variational) {
    Eigen::Matrix2d A;
    A << 0.0, 1.0, -(kStiffness + 3.0 * kCubic * s.q * s.q) / kMass, -kDamping / kMass;
    r.Phi = A * s.Phi;
  } else {
    r.Phi.setZero();
  }
  return r;
}

/// One classical Runge-Kutta step of length h from time t.
inline DuffingState rk4_step(double t, const DuffingState& s, double h, double Omega,
                             bool variational) {
  auto axpy = [](const DuffingState& a, double c, const DuffingState& k) {
    DuffingState r;
    r.q = a.q + c * k.q;
    r.v = a.v + c * k.v;
    r.Phi = a.Phi + c * k.Phi;
    return r;
  };
  const DuffingState k1 = duffing_rate(t, s, Omega, variational);
  const DuffingState k2 = duffing_rate(t + 0.5 * h, axpy(s, 0.5 * h, k1), Omega, variational);
  const DuffingState k3 = duffing_rate(t + 0.5 * h, axpy(s, 0.5 * h, k2), Omega, variational);
  const DuffingState k4 = duffing_rate(t + h, axpy(s, h, k3), Omega, variational);
  DuffingState r;
  r.q = s.q + h / 6.0 * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
  r.v = s.v + h / 6.0 * (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v);
  r.Phi = s.Phi + h / 6.0 * (k1.Phi + 2.0 * k2.Phi + 2.0 * k3.Phi + k4.Phi);
  return r;
}

}  // namespace geardyn::hbm::testing
