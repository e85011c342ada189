// A and C frequency weightings vs IEC 61672-1:2013 "Electroacoustics - Sound level meters -
// Part 1: Specifications", Table 3 (weightings at the nominal frequencies, computed by the
// standard at the exact base-10 frequencies f = 1000 * 10^(x/10) Hz and rounded to 0.1 dB).
#include "geardyn/signal/weighting.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace geardyn::signal {
namespace {

struct Row {
  int x;     // exact frequency 1000 * 10^(x/10) Hz
  double a;  // A-weighting, dB
  double c;  // C-weighting, dB
};

// IEC 61672-1:2013 Table 3, nominal frequencies 10 Hz ... 20 kHz.
constexpr std::array<Row, 34> kTable = {{
    {-20, -70.4, -14.3}, {-19, -63.4, -11.2}, {-18, -56.7, -8.5}, {-17, -50.5, -6.2},
    {-16, -44.7, -4.4},  {-15, -39.4, -3.0},  {-14, -34.6, -2.0}, {-13, -30.2, -1.3},
    {-12, -26.2, -0.8},  {-11, -22.5, -0.5},  {-10, -19.1, -0.3}, {-9, -16.1, -0.2},
    {-8, -13.4, -0.1},   {-7, -10.9, 0.0},    {-6, -8.6, 0.0},    {-5, -6.6, 0.0},
    {-4, -4.8, 0.0},     {-3, -3.2, 0.0},     {-2, -1.9, 0.0},    {-1, -0.8, 0.0},
    {0, 0.0, 0.0},       {1, 0.6, 0.0},       {2, 1.0, -0.1},     {3, 1.2, -0.2},
    {4, 1.3, -0.3},      {5, 1.2, -0.5},      {6, 1.0, -0.8},     {7, 0.5, -1.3},
    {8, -0.1, -2.0},     {9, -1.1, -3.0},     {10, -2.5, -4.4},   {11, -4.3, -6.2},
    {12, -6.6, -8.5},    {13, -9.3, -11.2},
}};

TEST(Weighting, MatchesTheTabulatedValuesOfIec61672WithinTheirRounding) {
  // The table is the analytic function rounded to 0.1 dB: half a unit, 0.05 dB, plus 0.001 dB
  // for ties (12.5 Hz C-weighting is -11.249..., tabulated -11.2).
  for (const Row& r : kTable) {
    const double f = 1000.0 * std::pow(10.0, r.x / 10.0);
    EXPECT_NEAR(weighting_db(Weighting::A, f), r.a, 0.051) << f << " Hz";
    EXPECT_NEAR(weighting_db(Weighting::C, f), r.c, 0.051) << f << " Hz";
    EXPECT_EQ(weighting_db(Weighting::Z, f), 0.0);
  }
}

TEST(Weighting, IsZeroAtOneKilohertzAndMatchesTheStandardsNormalisationConstants) {
  EXPECT_NEAR(weighting_db(Weighting::A, 1000.0), 0.0, 1e-12);
  EXPECT_NEAR(weighting_db(Weighting::C, 1000.0), 0.0, 1e-12);
  // Far below f1 the A-weighting rises as f^4 (80 dB per decade), the C-weighting as f^2
  // (IEC 61672-1 Annex E, the zeros at 0 Hz): checked between 0.1 and 0.01 Hz to 0.01 dB.
  EXPECT_NEAR(weighting_db(Weighting::A, 0.1) - weighting_db(Weighting::A, 0.01), 80.0, 0.01);
  EXPECT_NEAR(weighting_db(Weighting::C, 0.1) - weighting_db(Weighting::C, 0.01), 40.0, 0.01);
  EXPECT_NEAR(weighting_power_factor(Weighting::A, 100.0),
              std::pow(10.0, weighting_db(Weighting::A, 100.0) / 10.0), 1e-15);
  EXPECT_THROW(weighting_db(Weighting::A, 0.0), std::invalid_argument);
  EXPECT_THROW(weighting_db(Weighting::C, -5.0), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::signal
