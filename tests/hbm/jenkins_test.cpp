// The Jenkins element of hbm/jenkins.hpp against its closed forms (Griffin 1980, J. Eng. Power
// 102:329; the energy per cycle 4 F (X - F/k) is also the reference) and its analytic
// AFT Jacobian against finite differences.
//
// System: spring k = 1e5 N/m in series with a slider of limit F = 10 N (F/k = 0.1 mm), driven by
// u = X cos theta. Tolerance of the closed-form checks: the force has a kink where stick turns
// into slip, which the n uniform samples place to within one step, so the Fourier coefficients
// and the trapezoidal loop area carry an O((2 pi / n)^2) error: 2.4e-6 for n = 4096; 1e-5 is
// asserted, and the error at n = 1024 must be larger (it converges as the sampling refines).
#include "geardyn/hbm/jenkins.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/core/error.hpp"

namespace geardyn::hbm {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double k = 1e5, F = 10.0;

struct ClosedForm {
  double k_eq, c_omega, energy;
};
ClosedForm griffin(double X) {
  if (X <= F / k) return {k, 0.0, 0.0};
  const double beta = std::acos(1.0 - 2.0 * F / (k * X));
  return {k / kPi * (beta - 0.5 * std::sin(2.0 * beta)), 4.0 * F / (kPi * X) * (1.0 - F / (k * X)),
          4.0 * F * (X - F / k)};
}

// Largest relative error of k_eq, c_eq omega and the energy against the closed form.
double describing_function_error(double X, int n) {
  const HarmonicBasis b(1, n);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3);
  u[HarmonicBasis::cos_index(1)] = X;
  const JenkinsResponse r = jenkins_response({k, F}, b, u);
  const ClosedForm exact = griffin(X);
  const double k_eq = r.coefficients[HarmonicBasis::cos_index(1)] / X;
  const double c_omega = -r.coefficients[HarmonicBasis::sin_index(1)] / X;
  const double scale = exact.k_eq + exact.c_omega;  // both are O(k) or O(F / X)
  double err = std::max(std::abs(k_eq - exact.k_eq), std::abs(c_omega - exact.c_omega)) / scale;
  if (exact.energy > 0.0) {
    err = std::max(err, std::abs(r.energy_per_cycle - exact.energy) / exact.energy);
    // The loop area equals pi X^2 c_eq omega from the first sine coefficient.
    err = std::max(err, std::abs(kPi * X * X * c_omega - exact.energy) / exact.energy);
  } else {
    err = std::max(err, std::abs(r.energy_per_cycle) / (k * X * X));
  }
  return err;
}

TEST(Jenkins, DescribingFunctionAndEnergyMatchGriffin) {
  // (At X = 2F/k the stick-slip switch falls exactly on a sample, theta = pi/2, and both
  // samplings are exact to round-off; the amplitudes here avoid that coincidence.)
  for (double X : {1.5e-4, 3e-4, 5e-4, 2e-3, 2e-2}) {
    const double fine = describing_function_error(X, 4096);
    EXPECT_LT(fine, 1e-5) << "X = " << X;
    EXPECT_GT(describing_function_error(X, 1024), fine) << "X = " << X;
  }
}

TEST(Jenkins, StuckBelowTheSlipAmplitudeDissipatesNothing) {
  for (double X : {1e-6, 5e-5, 0.99e-4}) {
    const HarmonicBasis b(3, 256);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(b.size());
    u[0] = 3e-3;  // a mean offset: the element sticks about it
    u[HarmonicBasis::cos_index(1)] = X;
    const JenkinsResponse r = jenkins_response({k, F}, b, u);
    EXPECT_EQ(r.stick_fraction, 1.0);
    EXPECT_NEAR(r.coefficients[HarmonicBasis::cos_index(1)], k * X, 1e-9 * k * X);
    EXPECT_NEAR(r.coefficients[0], 0.0, 1e-12 * k * X);
    EXPECT_NEAR(r.energy_per_cycle, 0.0, 1e-12 * k * X * X);
  }
}

TEST(Jenkins, LimitsOfTheFrictionForce) {
  const HarmonicBasis b(3, 256);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(b.size());
  u[HarmonicBasis::cos_index(1)] = 1e-3;
  u[HarmonicBasis::sin_index(2)] = 4e-4;
  // No friction force: nothing transmitted.
  EXPECT_LT(jenkins_response({k, 0.0}, b, u).force.cwiseAbs().maxCoeff(), 1e-300);
  // A slip limit no motion reaches: the linear spring k (u - a_0).
  const JenkinsResponse stuck = jenkins_response({k, 1e9}, b, u);
  Eigen::VectorXd expected = k * u;
  expected[0] = 0.0;
  EXPECT_LT((stuck.coefficients - expected).cwiseAbs().maxCoeff(), 1e-9 * k * 1e-3);
  EXPECT_THROW((void)jenkins_response({0.0, F}, b, u), InputError);
  EXPECT_THROW((void)jenkins_response({k, -1.0}, b, u), InputError);
}

// The analytic Jacobian against central differences, for a multi-harmonic motion that sticks
// and slips several times per period. Differences with step h = 1e-7 X: truncation O(h^2) is
// nil for the piecewise-linear marching unless a stick/slip switch moves across a sample, and
// round-off is ~1e-16 / 1e-7 = 1e-9 relative; 1e-6 of the Jacobian's largest entry is asserted.
TEST(Jenkins, AnalyticJacobianMatchesFiniteDifferences) {
  const HarmonicBasis b(3, 512);
  Eigen::VectorXd u(b.size());
  u << 2e-5, 6e-4, -1e-4, 1.5e-4, 2e-4, -8e-5, 5e-5;
  const JenkinsResponse r = jenkins_response({k, F}, b, u);
  ASSERT_GT(r.stick_fraction, 0.05);
  ASSERT_LT(r.stick_fraction, 0.95);
  const double h = 1e-7 * 6e-4;
  Eigen::MatrixXd fd(b.size(), b.size());
  for (int c = 0; c < b.size(); ++c) {
    Eigen::VectorXd up = u, down = u;
    up[c] += h;
    down[c] -= h;
    fd.col(c) = (jenkins_response({k, F}, b, up).coefficients -
                 jenkins_response({k, F}, b, down).coefficients) /
                (2.0 * h);
  }
  const double scale = r.jacobian.cwiseAbs().maxCoeff();
  EXPECT_LT((r.jacobian - fd).cwiseAbs().maxCoeff(), 1e-6 * scale);
}

// The reference the stick-interval Jacobian replaces: the gradient g = dT/dc marched with the
// force, g += k (Q_j - Q_{j-1}) in stick, g = 0 where the force is clipped (jenkins.hpp).
Eigen::MatrixXd marched_jacobian(double kk, double FF, const HarmonicBasis& b,
                                 const Eigen::VectorXd& c) {
  const int n = b.time_samples(), m = b.size();
  const Eigen::VectorXd u = b.to_time(c);
  const Eigen::MatrixXd& Q = b.sampling();
  double T = kk * (u[0] - c[0]);
  Eigen::RowVectorXd g = kk * (Q.row(0) - Eigen::RowVectorXd::Unit(m, 0));
  auto clip = [&]() {
    if (std::abs(T) >= FF) {
      T = FF * (T >= 0.0 ? 1.0 : -1.0);
      g.setZero();
    }
  };
  clip();
  Eigen::MatrixXd G(n, m);
  for (int s = 1; s < 2 * n; ++s) {
    const int j = s % n, previous = (s - 1) % n;
    T += kk * (u[j] - u[previous]);
    g += kk * (Q.row(j) - Q.row(previous));
    clip();
    if (s >= n) G.row(j) = g;
  }
  return b.projection() * G;
}

// The force-only march (no Jacobian asked) gives the same force bit for bit, and the Jacobian
// from the stick intervals equals the marched gradient's to round-off: both sum the same
// k (Q_j - Q_a) terms, the march incrementally over up to 2 n steps (n = 512 steps of entries
// ~k: ~1e-13 k), so 1e-11 of k is asserted. Motions: stick-slip several times per period, a
// loop that never slips (the mean-anchored spring) and one clipped at its first sample.
TEST(Jenkins, ForceOnlyMarchAndStickIntervalJacobianEqualTheMarchedOnes) {
  const HarmonicBasis b(3, 512);
  using Coefficients = Eigen::Matrix<double, 7, 1>;  // H = 3
  const Coefficients slipping{{2e-5, 6e-4, -1e-4, 1.5e-4, 2e-4, -8e-5, 5e-5}};
  const Coefficients stuck{{3e-3, 5e-5, 2e-5, 0.0, 1e-5, 0.0, 0.0}};
  const Coefficients clipped{{0.0, 8e-4, 0.0, 0.0, 0.0, 0.0, 0.0}};
  for (const Coefficients& fixed : {slipping, stuck, clipped}) {
    const Eigen::VectorXd u = fixed;
    const JenkinsResponse full = jenkins_response({k, F}, b, u);
    const JenkinsResponse force_only = jenkins_response({k, F}, b, u, false);
    EXPECT_EQ(force_only.jacobian.size(), 0);
    EXPECT_TRUE(force_only.force == full.force);
    EXPECT_TRUE(force_only.coefficients == full.coefficients);
    EXPECT_EQ(force_only.stick_fraction, full.stick_fraction);
    EXPECT_LT((full.jacobian - marched_jacobian(k, F, b, u)).cwiseAbs().maxCoeff(), 1e-11 * k);
  }
}

}  // namespace
}  // namespace geardyn::hbm
