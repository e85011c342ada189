// Levels, radiation efficiency, the spherical radiator's limits and the ERP density map
// (acoustics/radiation.hpp), against hand computations.
#include "geardyn/acoustics/radiation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::acoustics {
namespace {

TEST(Levels, SoundPowerAndPressureLevelsByHand) {
  // L_W = 10 lg(P / 1e-12 W) (ISO 1683 reference power): 1 pW -> 0 dB, 1 W -> 120 dB,
  // 1 mW -> 90 dB. Exact decimal logarithms: 1e-12 dB.
  EXPECT_NEAR(sound_power_level_db(1e-12), 0.0, 1e-12);
  EXPECT_NEAR(sound_power_level_db(1.0), 120.0, 1e-12);
  EXPECT_NEAR(sound_power_level_db(1e-3), 90.0, 1e-12);
  EXPECT_EQ(sound_power_level_db(0.0), -std::numeric_limits<double>::infinity());
  // Free field, Q = 1, r = 1 m: L_p = L_W - 10 lg(4 pi) = 120 - 10.992099 dB; each doubling of
  // the distance -6.0206 dB (20 lg 2), Q = 2 (hemisphere over a reflecting plane) +3.0103 dB.
  EXPECT_NEAR(sound_pressure_level_db(1.0, 1.0), 109.0079, 1e-4);
  EXPECT_NEAR(sound_pressure_level_db(1.0, 2.0), 109.0079 - 6.0206, 1e-4);
  EXPECT_NEAR(sound_pressure_level_db(1.0, 1.0, 2.0), 109.0079 + 3.0103, 1e-4);
  // The e-axle study's reading: 1 m from a radiator of 1 mW, Q = 1: 79.0079 dB.
  EXPECT_NEAR(sound_pressure_level_db(1e-3, 1.0), 79.0079, 1e-4);
  EXPECT_THROW(sound_pressure_level_db(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(sound_pressure_level_db(1.0, 1.0, 0.0), std::invalid_argument);
}

TEST(SphericalRadiator, LimitsOfTheZeroOrderRadiator) {
  // P = 2 pi R^2 v^2 rho c (kR)^2 / (1 + (kR)^2): at kR = 1 half the plane-wave value
  // 2 pi R^2 rho c v^2 (= rho c S v^2 / 2, S = 4 pi R^2); for kR >> 1 it tends to it; for
  // kR << 1 it is rho c S v^2 (kR)^2 / 2 (Kinsler, Frey, Coppens and Sanders, "Fundamentals of
  // Acoustics", 4th ed., 2000, ch. 7). Hand values, round-off tolerances.
  const Air air;
  const double R = 0.15, v = 1e-3;
  const double plane = 2 * std::numbers::pi * R * R * air.impedance() * v * v;
  const double wK = air.speed_of_sound / R;
  EXPECT_NEAR(spherical_radiator_power(v, R, wK, air), plane / 2, 1e-15 * plane);
  EXPECT_NEAR(spherical_radiator_power(v, R, 1e4 * wK, air), plane, 1e-8 * plane);
  EXPECT_NEAR(spherical_radiator_power(v, R, 1e-3 * wK, air), plane * 1e-6, 1e-11 * plane);
  EXPECT_DOUBLE_EQ(equivalent_sphere_radius(4 * std::numbers::pi * R * R), R);
  EXPECT_THROW(spherical_radiator_power(v, 0.0, wK, air), std::invalid_argument);
}

TEST(RadiationEfficiencyTable, InterpolatesInLogFrequencyAndHoldsTheEnds) {
  const RadiationEfficiency constant(0.6);
  EXPECT_TRUE(constant.is_constant());
  EXPECT_EQ(constant.at(10.0), 0.6);
  EXPECT_EQ(constant.at(1e4), 0.6);
  const RadiationEfficiency table({100.0, 1000.0, 4000.0}, {0.1, 1.0, 1.0});
  // lg f halfway between 100 and 1000 Hz is sqrt(1e5) = 316.23 Hz: sigma 0.55.
  EXPECT_NEAR(table.at(std::sqrt(1e5)), 0.55, 1e-12);
  EXPECT_NEAR(table.at(200.0), 0.1 + 0.9 * std::log10(2.0), 1e-12);
  EXPECT_EQ(table.at(50.0), 0.1);
  EXPECT_EQ(table.at(1000.0), 1.0);
  EXPECT_EQ(table.at(2e4), 1.0);
  EXPECT_THROW(RadiationEfficiency({100.0, 100.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(RadiationEfficiency({0.0, 100.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(RadiationEfficiency({100.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(RadiationEfficiency({100.0}, {-0.1}), std::invalid_argument);
  EXPECT_THROW(RadiationEfficiency(-1.0), std::invalid_argument);
}

TEST(ErpDensityMap, BinsFacePowerPerAreaOnThePlaneOfTheLargestExtents) {
  // A 0.4 x 0.2 x 0.01 m plate: the map lies in the x-y plane; with a density uniform over the
  // top and bottom faces every filled cell reads it back (sum of powers / sum of areas).
  const solid::Mesh mesh =
      solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.4, 0.2, 0.01), 8, 4, 1,
                      solid::ElementType::Hex8, {"steel", 1, 2.1e11, 0.3, 7850, {}});
  const Surface s = exterior_surface(mesh);
  Eigen::VectorXd power(static_cast<Eigen::Index>(s.faces.size()));
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    power[static_cast<Eigen::Index>(f)] = 3.0 * s.faces[f].area;  // 3 W/m^2 everywhere
  const ErpDensityMap map = erp_density_map(s, power, 8);
  EXPECT_EQ(map.x_axis, 0);
  EXPECT_EQ(map.y_axis, 1);
  EXPECT_EQ(map.x_label, "x [m]");
  EXPECT_EQ(map.y_label, "y [m]");
  ASSERT_TRUE(map.trace.is_heatmap());
  ASSERT_EQ(map.trace.x.size(), 8u);
  ASSERT_EQ(map.trace.y.size(), 4u);
  ASSERT_EQ(map.trace.z.size(), 4u);
  int filled = 0;
  for (const auto& row : map.trace.z)
    for (double z : row)
      if (!std::isnan(z)) {
        EXPECT_NEAR(z, 3.0, 1e-12);
        ++filled;
      }
  EXPECT_EQ(filled, 32);
  EXPECT_THROW(erp_density_map(s, power.head(3), 8), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::acoustics
