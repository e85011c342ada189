// The AFT transforms of hbm/harmonic_basis.hpp: exact round trips for band-limited series (the
// samples determine every kept harmonic when n_time > 2H), agreement of the FFT path with the
// explicit sampling and projection matrices, and the sample-count rule. Tolerances are round-off
// of FFTs of length <= 1024 (1e-13 relative).
#include "geardyn/hbm/harmonic_basis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/core/error.hpp"

namespace geardyn::hbm {
namespace {

TEST(HarmonicBasis, RoundTripAndMatricesAgree) {
  for (const auto& [H, n] : {std::pair{1, 3}, std::pair{5, 64}, std::pair{7, 100}}) {
    const HarmonicBasis b(H, n);
    ASSERT_EQ(b.size(), 2 * H + 1);
    const Eigen::VectorXd c = Eigen::VectorXd::Random(b.size());
    const Eigen::VectorXd x = b.to_time(c);
    EXPECT_LT((x - b.sampling() * c).cwiseAbs().maxCoeff(), 1e-13) << H << " " << n;
    EXPECT_LT((b.to_frequency(x) - c).cwiseAbs().maxCoeff(), 1e-13) << H << " " << n;
    EXPECT_LT((b.projection() * x - c).cwiseAbs().maxCoeff(), 1e-13) << H << " " << n;
  }
}

TEST(HarmonicBasis, CoefficientLayout) {
  // x = 0.5 + 2 cos(3 theta) - 4 sin(theta) sampled at theta_j = 2 pi j / n.
  const HarmonicBasis b(3, 32);
  Eigen::VectorXd x(32);
  for (int j = 0; j < 32; ++j) {
    const double theta = 2.0 * std::numbers::pi * j / 32;
    x[j] = 0.5 + 2.0 * std::cos(3 * theta) - 4.0 * std::sin(theta);
  }
  const Eigen::VectorXd c = b.to_frequency(x);
  EXPECT_NEAR(c[HarmonicBasis::cos_index(0)], 0.5, 1e-14);
  EXPECT_NEAR(c[HarmonicBasis::cos_index(3)], 2.0, 1e-14);
  EXPECT_NEAR(c[HarmonicBasis::sin_index(1)], -4.0, 1e-14);
  EXPECT_NEAR(c.cwiseAbs().sum(), 6.5, 1e-13);
}

TEST(HarmonicBasis, SampleCountsAndErrors) {
  EXPECT_EQ(default_time_samples(1), 64);
  EXPECT_EQ(default_time_samples(5, 3), 64);      // 4 * 5 + 1 = 21 -> at least 64
  EXPECT_EQ(default_time_samples(50, 8), 512);    // 9 * 50 + 1 = 451 -> 512
  EXPECT_THROW(HarmonicBasis(4, 8), InputError);  // 8 < 2 * 4 + 1
  EXPECT_THROW(HarmonicBasis(-1, 8), InputError);
  const HarmonicBasis b(2, 16);
  EXPECT_THROW((void)b.to_time(Eigen::VectorXd::Zero(4)), InputError);
  EXPECT_THROW((void)b.to_frequency(Eigen::VectorXd::Zero(15)), InputError);
}

}  // namespace
}  // namespace geardyn::hbm
