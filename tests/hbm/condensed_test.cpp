// Condensation of the harmonic balance to the nonlinear coordinates (hbm/condensed.hpp) against
// the uncondensed harmonic balance of the same system (hbm/harmonic_balance.hpp).
//
// System: a chain of three masses (m = 1, 1, 0.5 kg; springs 1, 1, 2 N/m, the first to ground),
// stiffness-proportional damping C = 0.004 K (exactly modal: zeta_r = 0.002 w_r), a force
// 0.02 cos(w t) on mass 0 and a Jenkins friction element (k_t = 0.8 N/m, slip force 0.01 N)
// between mass 2 and the ground -- the only nonlinear coordinate. With every mode kept, the
// receptance form  X_c = X_lin - H F_nl  is an exact rewriting of  D X + F_nl = F_ext  (Krack &
// Gross, "Harmonic Balance for Nonlinear Vibration Problems", Springer 2019, sec. 3.4), so both
// must give the same periodic solutions: the nonlinear coordinate and the recovered sensor (mass
// 0) agree to the Newton tolerance (1e-10 relative is asserted; the solves are at 1e-12).
// With the highest mode left out, the residual flexibility (its static contribution) must bring
// the condensed answer closer to the exact one than the plain truncated modal sum. The static
// correction is exact at w = 0 and misses the left-out mode's dynamic part, of relative order
// (w / w_3)^2 (w_3 = 2.3 rad/s): below 10 % of the truncation error at 0.3 and 0.45 rad/s, below
// 50 % near the second resonance (0.6 and 0.75 rad/s; measured 3e-1 there), where small shifts
// of the peak dominate.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/condensed.hpp"

namespace geardyn::hbm {
namespace {

struct Chain {
  Eigen::MatrixXd M, K, C;
  Chain() {
    M = Eigen::Vector3d(1.0, 1.0, 0.5).asDiagonal();
    K.resize(3, 3);
    K << 2.0, -1.0, 0.0,  //
        -1.0, 3.0, -2.0,  //
        0.0, -2.0, 2.0;
    C = 0.004 * K;
  }
};

constexpr double kForce = 0.02;
const JenkinsElement kElement{0.8, 0.01};

HarmonicBalance physical(const Chain& s, const HarmonicBasis& basis) {
  const Eigen::VectorXd F =
      kForce * Eigen::VectorXd::Unit(3 * basis.size(), HarmonicBasis::cos_index(1));
  return HarmonicBalance(s.M, s.C, s.K, basis, {jenkins_force(2, -1, kElement)}, F);
}

// Coordinate: DOF 2; sensor: DOF 0. `kept` lowest modes; with `residual` the static flexibility
// of the others.
CondensedHarmonicBalance condensed(const Chain& s, const HarmonicBasis& basis, int kept,
                                   bool residual) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.K, s.M);
  const Eigen::VectorXd w = eig.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd phi = eig.eigenvectors();  // mass-normalised
  const Eigen::MatrixXd flex = s.K.inverse();
  std::vector<ModalReceptance> harmonics;
  for (int n = 0; n <= basis.harmonics(); ++n) {
    ModalReceptance r;
    r.natural_frequency = w.head(kept);
    r.damping_ratio = 0.002 * w.head(kept);
    r.left = phi.block(2, 0, 1, kept).cast<std::complex<double>>();
    r.right = r.left;
    r.sensor_left = phi.block(0, 0, 1, kept).cast<std::complex<double>>();
    if (n == 1) r.modal_excitation = kForce * phi.block(0, 0, 1, kept).transpose().cast<std::complex<double>>();
    if (residual) {
      // Static flexibility minus the kept modes' static part.
      Eigen::MatrixXd modal_static = phi.leftCols(kept) * w.head(kept).cwiseInverse().cwiseAbs2().asDiagonal() *
                                     phi.leftCols(kept).transpose();
      const Eigen::MatrixXd rest = flex - modal_static;
      r.residual = Eigen::MatrixXcd::Constant(1, 1, rest(2, 2));
      r.sensor_residual = Eigen::MatrixXcd::Constant(1, 1, rest(0, 2));
      if (n == 1) {
        r.residual_excitation = Eigen::VectorXcd::Constant(1, kForce * rest(2, 0));
        r.sensor_residual_excitation = Eigen::VectorXcd::Constant(1, kForce * rest(0, 0));
      }
    }
    harmonics.push_back(r);
  }
  return CondensedHarmonicBalance(1, basis, harmonics, {jenkins_force(0, -1, kElement)});
}

ContinuationOptions options(double x_scale) {
  ContinuationOptions o;
  o.omega_start = 0.3;
  o.omega_end = 0.9;
  o.x_scale = x_scale;
  o.omega_scale = 0.6;
  o.step = 0.02;
  o.max_step = 0.05;
  o.tolerance = 1e-12;
  return o;
}

// Solutions at the frequencies `w` (increasing), by Newton at each, started from the previous
// solution; intermediate frequencies at most 0.005 apart keep each start close.
std::vector<Eigen::VectorXd> solve_points(const HarmonicSystem& hb, const std::vector<double>& w,
                                          Eigen::VectorXd X) {
  std::vector<Eigen::VectorXd> out;
  double current = w.front();
  for (double target : w) {
    const int sub = std::max(1, static_cast<int>(std::ceil((target - current) / 0.005)));
    for (int k = 1; k <= sub; ++k) {
      const double omega = current + (target - current) * k / sub;
      Eigen::MatrixXd J;
      bool converged = false;
      for (int it = 0; it < 50 && !converged; ++it) {
        const Eigen::VectorXd R = hb.residual(X, omega, &J);
        converged = R.norm() <= 1e-13 * hb.residual_scale(X, omega);
        if (!converged) X -= J.partialPivLu().solve(R);
      }
      EXPECT_TRUE(converged) << "at " << omega;
    }
    current = target;
    out.push_back(X);
  }
  return out;
}

TEST(CondensedHarmonicBalance, EqualsTheUncondensedSolutionWithAllModes) {
  const HarmonicBasis basis(5, 256);
  const Chain s;
  const HarmonicBalance full = physical(s, basis);
  const CondensedHarmonicBalance cond = condensed(s, basis, 3, false);
  const int sz = basis.size();
  std::vector<double> w;
  for (int i = 0; i <= 60; ++i) w.push_back(0.3 + 0.01 * i);
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  const auto xc = solve_points(cond, w, Eigen::VectorXd::Zero(cond.size()));
  double worst = 0.0, worst_sensor = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Eigen::VectorXd coordinate = xf[i].segment(2 * sz, sz);
    worst = std::max(worst, (coordinate - xc[i]).norm() / coordinate.norm());
    largest = std::max(largest, coordinate.norm());
    // Recovery at mass 0, harmonics 1 and 3.
    for (int n : {1, 3}) {
      const std::complex<double> exact(xf[i][HarmonicBasis::cos_index(n)],
                                       -xf[i][HarmonicBasis::sin_index(n)]);
      const std::complex<double> recovered = cond.sensor_response(xc[i], w[i], n)[0];
      worst_sensor = std::max(worst_sensor, std::abs(recovered - exact) /
                                                xf[i].segment(0, sz).norm());
    }
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_sensor, 1e-10);
  EXPECT_GT(largest, 0.05);  // the sweep crosses a resonance: the friction element slips
}

TEST(CondensedHarmonicBalance, ContinuationWithScalingMatchesFixedFrequencySolves) {
  const HarmonicBasis basis(3, 128);
  const Chain s;
  const CondensedHarmonicBalance cond = condensed(s, basis, 3, false);
  const ContinuationResult r = continue_in_frequency(cond, Eigen::VectorXd::Zero(cond.size()),
                                                     options(0.05));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GT(r.points.size(), 20u);
  const HarmonicBalance full = physical(s, basis);
  std::vector<double> w;
  for (const auto& p : r.points) w.push_back(p.omega);
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& p = r.points[i];
    const Eigen::VectorXd c = xf[i].segment(2 * basis.size(), basis.size());
    EXPECT_LT((c - p.X).norm(), 1e-8 * std::max(1e-3, c.norm())) << "at " << p.omega;
  }
}

TEST(CondensedHarmonicBalance, ResidualFlexibilityCorrectsATruncatedModalSum) {
  const HarmonicBasis basis(3, 128);
  const Chain s;
  const HarmonicBalance full = physical(s, basis);
  const CondensedHarmonicBalance truncated = condensed(s, basis, 2, false);
  const CondensedHarmonicBalance corrected = condensed(s, basis, 2, true);
  const std::vector<double> w{0.3, 0.45, 0.6, 0.75};
  const auto xf = solve_points(full, w, Eigen::VectorXd::Zero(full.size()));
  const auto xt = solve_points(truncated, w, Eigen::VectorXd::Zero(truncated.size()));
  const auto xr = solve_points(corrected, w, Eigen::VectorXd::Zero(corrected.size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const Eigen::VectorXd c = xf[i].segment(2 * basis.size(), basis.size());
    const double e_trunc = (xt[i] - c).norm(), e_corr = (xr[i] - c).norm();
    EXPECT_LT(e_corr, (w[i] < 0.5 ? 0.1 : 0.5) * e_trunc) << "at " << w[i];
  }
}

TEST(CondensedHarmonicBalance, AMeanWithoutReceptanceIsHeldAtZero) {
  // A static load on mass 0 moves the mean of the coordinate when harmonic 0 has its
  // receptance, and not when the harmonic-0 entry is empty.
  const HarmonicBasis basis(2, 64);
  const Chain s;
  std::vector<ModalReceptance> h = condensed(s, basis, 3, false).harmonics();
  h[0].modal_excitation = 0.01 * h[0].sensor_left.row(0).transpose();
  const CondensedHarmonicBalance free(1, basis, h, {cubic_spring(0, 5.0)});
  h[0] = ModalReceptance{};
  const CondensedHarmonicBalance fixed(1, basis, h, {cubic_spring(0, 5.0)});
  const auto xf = solve_points(free, {0.5}, Eigen::VectorXd::Zero(free.size()))[0];
  const auto xh = solve_points(fixed, {0.5}, Eigen::VectorXd::Zero(fixed.size()))[0];
  EXPECT_GT(std::abs(xf[0]), 1e-3);
  EXPECT_EQ(xh[0], 0.0);
  EXPECT_GT(std::abs(xh[HarmonicBasis::cos_index(1)]), 1e-3);
}

TEST(CondensedHarmonicBalance, RejectsMismatchedReceptances) {
  const HarmonicBasis basis(1, 16);
  ModalReceptance r;
  r.natural_frequency = Eigen::VectorXd::Ones(2);
  r.damping_ratio = Eigen::VectorXd::Zero(2);
  r.left = Eigen::MatrixXcd::Zero(1, 2);
  r.right = Eigen::MatrixXcd::Zero(1, 3);
  EXPECT_THROW(CondensedHarmonicBalance(1, basis, {ModalReceptance{}, r}, std::vector<NonlinearForce>{}), InputError);
  EXPECT_THROW(CondensedHarmonicBalance(1, basis, {ModalReceptance{}}, std::vector<NonlinearForce>{}),
               InputError);
}

}  // namespace
}  // namespace geardyn::hbm
