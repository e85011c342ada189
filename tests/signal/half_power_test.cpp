// Unit tests of signal/half_power: parabolic vertex, peak prominence, half-power crossings.
#include "geardyn/signal/half_power.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace geardyn::signal {
namespace {

TEST(ParabolicVertex, ExactForAParabolaWithUnequalSpacing) {
  // y = 3 - 2 (x - 1.3)^2: vertex (1.3, 3) from any three points.
  auto y = [](double x) { return 3.0 - 2.0 * (x - 1.3) * (x - 1.3); };
  const auto v = parabolic_vertex(0.2, y(0.2), 1.1, y(1.1), 2.9, y(2.9));
  ASSERT_TRUE(v.valid);
  EXPECT_NEAR(v.x, 1.3, 1e-14);
  EXPECT_NEAR(v.y, 3.0, 1e-14);
}

TEST(ParabolicVertex, NoMaximumForCollinearOrConvexPoints) {
  EXPECT_FALSE(parabolic_vertex(0, 0, 1, 1, 2, 2).valid);
  EXPECT_FALSE(parabolic_vertex(0, 1, 1, 0, 2, 1).valid);
  EXPECT_FALSE(parabolic_vertex(1, 1, 1, 2, 2, 1).valid);  // repeated abscissa
}

TEST(FindPeaks, ProminenceFollowsTheTopographicDefinition) {
  //                 0  1  2  3  4  5  6  7  8  9
  std::vector<double> y{0, 5, 1, 3, 2, 8, 8, 8, 0, 4};
  // Peak 1 (5): left base 0, right: walk to 8 (higher) -> base min(1,3,2) = 1 -> prominence 4.
  // Peak 3 (3): bases 1 (left, stops at 5) and 2 (right, stops at 8) -> 1.
  // Plateau 5..7 (8): highest, bases 0 and 0 -> 8, reported at its middle (6).
  // 9 is the last sample: not a peak.
  const auto all = find_peaks(y, 0.0);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].index, 1u);
  EXPECT_DOUBLE_EQ(all[0].prominence, 4.0);
  EXPECT_EQ(all[1].index, 3u);
  EXPECT_DOUBLE_EQ(all[1].prominence, 1.0);
  EXPECT_EQ(all[2].index, 6u);
  EXPECT_DOUBLE_EQ(all[2].prominence, 8.0);
  const auto big = find_peaks(y, 2.0);
  ASSERT_EQ(big.size(), 2u);
  EXPECT_EQ(big[0].index, 1u);
  EXPECT_EQ(big[1].index, 6u);
}

TEST(FindPeaks, RejectsNaN) {
  std::vector<double> y{0, 1, std::nan(""), 0};
  EXPECT_THROW(find_peaks(y, 0.0), std::invalid_argument);
}

TEST(HalfPower, TriangleGivesExactLinearCrossings) {
  // A symmetric triangle of height 1 over [0, 2] sampled at 0, 0.5, 1, 1.5, 2 is piecewise
  // linear between samples, so linear interpolation is exact: the level 1/sqrt(2) is crossed
  // at 1 -/+ (1 - 1/sqrt(2)); the parabola through the top three samples has its vertex at 1
  // but its value 1 equals the sample, so the peak stays at (1, 1).
  std::vector<double> f{0, 0.5, 1.0, 1.5, 2.0}, a{0, 0.5, 1.0, 0.5, 0};
  const auto hp = half_power(f, a, 2);
  ASSERT_TRUE(hp.has_bandwidth());
  const double half = 1.0 - 1.0 / std::sqrt(2.0);
  EXPECT_NEAR(hp.f1, 1.0 - half, 1e-15);
  EXPECT_NEAR(hp.f2, 1.0 + half, 1e-15);
  EXPECT_NEAR(hp.q_factor, 1.0 / (2.0 * half), 1e-14);
  EXPECT_EQ(hp.lower_bracket, 1u);
  EXPECT_EQ(hp.upper_bracket, 2u);
  EXPECT_EQ(hp.points_in_band, 1);
}

TEST(HalfPower, StopsAtTheRangeEndOrAHigherPeak) {
  std::vector<double> f{0, 1, 2, 3, 4}, a{0.9, 1.0, 0.95, 2.0, 0.1};
  const auto hp = half_power(f, a, 1);
  EXPECT_FALSE(hp.has_lower());  // falls to 0.9 only, then the data end
  EXPECT_FALSE(hp.has_upper());  // runs into the higher peak at 3
  EXPECT_TRUE(std::isnan(hp.q_factor));
  EXPECT_THROW(half_power(f, a, 5), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
