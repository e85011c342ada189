// A friction-damped oscillator by harmonic balance, against its linear limits and against a
// time integration of the same system (issue #5, section 5):
//
//   m q'' + c q' + k q + T(q) = f cos(Omega t),   T: Jenkins element (k_t in series with a
//   slider of limit mu N) between the mass and the ground.
//   m = 1 kg, k = 1 N/m, c = 0.01 N s/m (zeta = 0.005), k_t = 1 N/m, f = 0.05 N.
//
// Limits: mu N -> infinity sticks the slider: a linear oscillator of stiffness k + k_t;
// mu N = 0 removes the element: stiffness k. In both the harmonic-balance curve must equal
// f / |k_eff - m Omega^2 + i c Omega| (1e-9: Newton tolerance, no approximation left).
// Between them, the multi-harmonic solution (H = 7) is checked against a time integration
// started on it: velocity Verlet with the damping implicit and the slider state updated per step
// (second order away from the stick-slip switches, first order across them), 4000 steps per
// period, 300 periods. The issue asks for 1 % on the peak amplitude; the integration error at
// this step is ~1e-4 and the truncation of the series at H = 7 below that.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm {
namespace {

constexpr double kM = 1.0, kK = 1.0, kC = 0.01, kKt = 1.0, kF = 0.05;

HarmonicBalance oscillator(int harmonics, double slip_force) {
  const HarmonicBasis basis(harmonics, 1024);
  std::vector<NonlinearForce> forces;
  forces.push_back(jenkins_force(0, -1, {kKt, slip_force}));
  return HarmonicBalance(Eigen::MatrixXd::Constant(1, 1, kM), Eigen::MatrixXd::Constant(1, 1, kC),
                         Eigen::MatrixXd::Constant(1, 1, kK), basis, forces,
                         kF * Eigen::VectorXd::Unit(basis.size(), HarmonicBasis::cos_index(1)));
}

ContinuationResult sweep(const HarmonicBalance& hb, double step) {
  ContinuationOptions o;
  o.omega_start = 0.6;
  o.omega_end = 1.8;
  o.step = step;
  o.max_step = step;
  o.tolerance = 1e-12;
  const double k0 = kK + kKt;  // a stuck start at low frequency
  const Eigen::VectorXd X0 =
      kF / (k0 - 0.36) * Eigen::VectorXd::Unit(hb.size(), HarmonicBasis::cos_index(1));
  return continue_in_frequency(hb, X0, o);
}

TEST(FrictionOscillator, LinearLimitsOfTheSlipForce) {
  for (const auto& [slip, k_eff] : {std::pair{1e6, kK + kKt}, std::pair{0.0, kK}}) {
    const HarmonicBalance hb = oscillator(3, slip);
    const ContinuationResult r = sweep(hb, 0.01);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_GT(r.points.size(), 50u);
    for (const auto& p : r.points) {
      const double exact =
          kF / std::abs(std::complex<double>(k_eff - kM * p.omega * p.omega, kC * p.omega));
      EXPECT_NEAR(hb.amplitude(p.X, 0, 1), exact, 1e-9 * exact)
          << "slip " << slip << " omega " << p.omega;
      EXPECT_NEAR(hb.amplitude(p.X, 0, 3), 0.0, 1e-9 * exact);
    }
  }
}

// Largest |q| over one period of the steady state by time integration at Omega, started on the
// harmonic-balance solution X (displacement and velocity at t = 0, slider force from the loop).
double integrated_peak(double omega, const HarmonicBasis& basis, const Eigen::VectorXd& X,
                       double slip) {
  const double period = 2.0 * std::numbers::pi / omega;
  const int per_period = 4000;
  const double dt = period / per_period;
  double q = X[0], v = 0.0;
  for (int n = 1; n <= basis.harmonics(); ++n)
    v += n * omega * X[HarmonicBasis::sin_index(n)], q += X[HarmonicBasis::cos_index(n)];
  const JenkinsResponse loop = jenkins_response({kKt, slip}, basis, X);
  double T = loop.force[0];
  double a = (kF - kC * v - kK * q - T) / kM;
  double peak = 0.0;
  const int periods = 300;
  for (int step = 1; step <= periods * per_period; ++step) {
    const double t = step * dt;
    const double q_new = q + dt * v + 0.5 * dt * dt * a;
    T += kKt * (q_new - q);
    T = std::clamp(T, -slip, slip);
    const double rest = (kF * std::cos(omega * t) - kK * q_new - T) / kM;
    const double v_new = (v + 0.5 * dt * (a + rest)) / (1.0 + 0.5 * dt * kC / kM);
    a = rest - kC * v_new / kM;
    q = q_new;
    v = v_new;
    if (step > (periods - 1) * per_period) peak = std::max(peak, std::abs(q));
  }
  return peak;
}

TEST(FrictionOscillator, HarmonicBalanceAgreesWithTimeIntegrationAtThePeak) {
  const double slip = 0.02;  // mu N: slips well before resonance
  const HarmonicBalance hb = oscillator(7, slip);
  const ContinuationResult r = sweep(hb, 0.01);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  // The time-domain peak of each point, and the largest over the sweep.
  std::size_t best = 0;
  std::vector<double> peak(r.points.size());
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    peak[i] = hb.basis().to_time(r.points[i].X).cwiseAbs().maxCoeff();
    if (peak[i] > peak[best]) best = i;
  }
  // Friction limits the resonance between the stuck (sqrt 2) and free (1) natural frequencies.
  const double omega_peak = r.points[best].omega;
  EXPECT_GT(omega_peak, 1.0);
  EXPECT_LT(omega_peak, std::sqrt(2.0));
  const double free_peak = kF / (kC * 1.0);  // 5 m: the undamped-by-friction resonance
  EXPECT_LT(peak[best], 0.5 * free_peak);
  for (std::size_t i : {best / 2, best, (best + r.points.size()) / 2}) {
    const double ti = integrated_peak(r.points[i].omega, hb.basis(), r.points[i].X, slip);
    EXPECT_NEAR(ti, peak[i], 0.01 * peak[i]) << "omega " << r.points[i].omega;
  }
}

}  // namespace
}  // namespace geardyn::hbm
