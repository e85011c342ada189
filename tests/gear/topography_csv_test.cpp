// The topological modification map (gear::TopographyMap, gear/tooth_contact.hpp): bilinear
// between its grid points, constant beyond its edges; and its CSV reader (gear/topography_csv.hpp)
// with located errors.
#include "geardyn/gear/topography_csv.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

namespace geardyn::gear {
namespace {

// A bilinear function a + b x + c y + d x y is reproduced exactly (to rounding, 1e-17 m of a
// micrometre map) by bilinear interpolation, anywhere inside the grid, on a non-uniform grid.
double bilinear(double xi, double y) { return 1e-6 + 2e-6 * xi - 3e-4 * y + 5e-3 * xi * y; }

TopographyMap sample_map() {
  TopographyMap m;
  m.roll_angle_rad = {0.1, 0.25, 0.6};
  m.face_m = {0.0, 0.004, 0.012, 0.02};
  m.removed_m.resize(3, 4);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      m.removed_m(i, k) = bilinear(m.roll_angle_rad[static_cast<std::size_t>(i)],
                                   m.face_m[static_cast<std::size_t>(k)]);
  return m;
}

TEST(TopographyMap, IsBilinearInsideTheGrid) {
  const TopographyMap m = sample_map();
  for (double xi : {0.1, 0.13, 0.25, 0.4, 0.6})
    for (double y : {0.0, 0.001, 0.004, 0.0111, 0.02})
      EXPECT_NEAR(m.at(xi, y), bilinear(xi, y), 1e-17) << xi << " " << y;
}

TEST(TopographyMap, IsConstantBeyondItsEdges) {
  const TopographyMap m = sample_map();
  EXPECT_NEAR(m.at(0.0, 0.006), bilinear(0.1, 0.006), 1e-17);  // below the first roll angle
  EXPECT_NEAR(m.at(0.9, 0.006), bilinear(0.6, 0.006), 1e-17);  // beyond the last
  EXPECT_NEAR(m.at(0.3, -0.01), bilinear(0.3, 0.0), 1e-17);    // before y = 0
  EXPECT_NEAR(m.at(0.3, 0.05), bilinear(0.3, 0.02), 1e-17);    // beyond the face
  EXPECT_NEAR(m.at(-1.0, 1.0), bilinear(0.1, 0.02), 1e-17);    // a corner
  EXPECT_EQ(TopographyMap{}.at(0.3, 0.01), 0.0);               // no map: nothing removed
}

TEST(TopographyCsv, ReadsAGridInAnyOrderWithUnits) {
  std::string csv = "# pinion topography\nface_mm, roll_angle_deg, removed_um\n";
  const TopographyMap ref = sample_map();
  for (int k = 3; k >= 0; --k)
    for (int i = 0; i < 3; ++i)
      csv +=
          fmt::format("{:.17g}, {:.17g}, {:.17g}\n", ref.face_m[static_cast<std::size_t>(k)] * 1e3,
                      ref.roll_angle_rad[static_cast<std::size_t>(i)] * 180.0 / M_PI,
                      ref.removed_m(i, k) * 1e6);
  const TopographyMap m = parse_topography_csv(csv, "topo.csv");
  ASSERT_EQ(m.roll_angle_rad.size(), 3u);
  ASSERT_EQ(m.face_m.size(), 4u);
  for (double xi : {0.12, 0.3, 0.5})
    for (double y : {0.002, 0.01, 0.019}) EXPECT_NEAR(m.at(xi, y), ref.at(xi, y), 1e-18);
}

TEST(TopographyCsv, BadFilesAreLocated) {
  auto error = [](const std::string& text) -> std::string {
    try {
      (void)parse_topography_csv(text, "topo.csv");
    } catch (const InputError& e) {
      return fmt::format("{}:{}:{} {} | {} | {}", e.where().file, e.where().line, e.where().column,
                         e.key_path(), e.expected(), e.found());
    }
    return "no error";
  };
  const std::string head = "roll_angle_deg, face_mm, removed_um\n";
  EXPECT_NE(error(head + "0, 0, 1\n0, 20, 1\n30, 0, 1\n30, 0, 2\n")
                .find("topo.csv:5:1 "
                      "roll_angle_deg"),
            std::string::npos);
  EXPECT_NE(error(head + "0, 0, 1\n0, 20, 1\n30, 0, 1\n40, 20, 1\n")
                .find("no row at roll_angle_deg = 30, face_mm = 20"),
            std::string::npos);
  EXPECT_NE(error(head + "0, 0, 1\n0, 20, 1\n30, 0, 1\n30, 20, 2000\n").find(":5:9 removed_um"),
            std::string::npos);
  EXPECT_NE(error(head + "0, 0, 1\n0, 20, 1\n-3, 0, 1\n-3, 20, 1\n").find(":4:1 roll_angle_deg"),
            std::string::npos);
  EXPECT_NE(error("roll_angle_deg, face_in, removed_um\n0,0,1\n0,1,1\n1,0,1\n1,1,1\n")
                .find(":1:17 face_in"),
            std::string::npos);
  EXPECT_NE(error("roll_angle_deg, removed_um\n0,1\n1,1\n2,1\n3,1\n").find("face_m or face_mm"),
            std::string::npos);
  EXPECT_NE(error(head + "0, 0, 1\n0, 20, 1\n0, 10, 1\n0, 5, 1\n").find("at least 2 distinct"),
            std::string::npos);
}

}  // namespace
}  // namespace geardyn::gear
