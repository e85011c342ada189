// Gear pairs with different face widths (b1 != b2) and the base helix angle in the geometry
// table, end to end from the model file.
//
// References:
//   ISO 21771:2007 (Gears - Cylindrical involute gears and gear pairs - Concepts and geometry):
//     tan(alpha_t) = tan(alpha_n) / cos(beta), tan(beta_b) = tan(beta) cos(alpha_t),
//     overlap ratio eps_beta = b sin(beta) / (pi m_n).
//   ISO 6336-1:2019 (Calculation of load capacity of spur and helical gears - Part 1): b, the
//     face width of the pair in the mesh stiffness c_gamma b, is the smaller of b1 and b2.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/core/error.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kPi = std::numbers::pi;

std::string helical(const std::string& widths) {
  return "version = 1\n[[gear_pairs]]\nname = \"h\"\ntype = \"helical\"\nteeth1 = 20\n"
         "teeth2 = 40\nmodule = 0.003\nhelix_angle_deg = 15\n" +
         widths + "torque = 100\n\n[[analyses]]\nname = \"pair\"\ntype = \"gear_pair\"\n";
}

AnalysisOutput run(const model::Model& m) {
  return type_of(m.analyses[0]).run(m, m.analyses[0], Context(m, m.analyses[0])).output;
}

TEST(GearPairWidths, UnequalWidthsUseTheSmallerForTheContact) {
  const fs::path dir = fresh_dir("gear_pair_widths");
  const model::Model m = load(dir, helical("face_width1 = 0.025\nface_width2 = 0.02\n"));
  EXPECT_EQ(m.gear_pairs[0].face_width, 0.02);
  const AnalysisOutput out = run(m);
  const Table& g = table(out, "gear_geometry");
  const std::size_t pinion = row_where(g, "member", "pinion"),
                    wheel = row_where(g, "member", "wheel");
  EXPECT_EQ(g.column("face_width_m").numbers[pinion], 0.025);
  EXPECT_EQ(g.column("face_width_m").numbers[wheel], 0.02);
  EXPECT_EQ(g.column("contact_face_width_m").numbers[pinion], 0.02);
  // Overlap ratio with b = min(b1, b2) = 20 mm; closed form, rounding only: 1e-12.
  const double beta = 15.0 * kPi / 180;
  const double eps_beta = 0.02 * std::sin(beta) / (kPi * 0.003);
  EXPECT_NEAR(g.column("overlap_ratio").numbers[0], eps_beta, 1e-12 * eps_beta);

  // The same pair with one width of 20 mm has the same stiffness and contact (bit for bit: the
  // contact width is the only width the computation uses).
  const model::Model same = load(dir, helical("face_width = 0.02\n"));
  const AnalysisOutput ref = run(same);
  EXPECT_EQ(table(out, "iso_stiffness").column("mesh_stiffness_n_per_m").numbers[0],
            table(ref, "iso_stiffness").column("mesh_stiffness_n_per_m").numbers[0]);
  EXPECT_EQ(table(ref, "gear_geometry").column("face_width_m").numbers[pinion], 0.02);
}

// tan(beta_b) = tan(beta) cos(alpha_t) (ISO 21771); the library computes it as
// asin(sin(beta) cos(alpha_n)), an equivalent form: agreement to round-off, 1e-12 deg.
TEST(GearPairWidths, BaseHelixAngleIsInTheGeometryTable) {
  const fs::path dir = fresh_dir("gear_pair_beta_b");
  const AnalysisOutput out = run(load(dir, helical("face_width = 0.02\n")));
  const Table& g = table(out, "gear_geometry");
  const double beta = 15.0 * kPi / 180, alpha_n = 20.0 * kPi / 180;
  const double alpha_t = std::atan(std::tan(alpha_n) / std::cos(beta));
  const double beta_b_deg = std::atan(std::tan(beta) * std::cos(alpha_t)) * 180 / kPi;
  for (std::size_t i = 0; i < g.rows(); ++i)
    EXPECT_NEAR(g.column("base_helix_angle_deg").numbers[i], beta_b_deg, 1e-12);
  EXPECT_NEAR(beta_b_deg, 14.076, 1e-3);  // the textbook value for 15 deg / 20 deg
}

TEST(GearPairWidths, WidthKeysAreCheckedTogether) {
  const fs::path dir = fresh_dir("gear_pair_width_keys");
  const auto error = [&](const std::string& widths) {
    try {
      (void)load(dir, helical(widths));
    } catch (const InputError& e) {
      return std::string(e.key_path()) + ": " + e.expected();
    }
    return std::string("no error");
  };
  EXPECT_NE(error("face_width1 = 0.025\n")
                .find("gear_pairs[0].face_width1: face_width1 and "
                      "face_width2 together"),
            std::string::npos)
      << error("face_width1 = 0.025\n");
  EXPECT_NE(
      error("face_width = 0.02\nface_width1 = 0.025\nface_width2 = 0.02\n").find("only one of"),
      std::string::npos);
  EXPECT_NE(error("").find("one of"), std::string::npos) << error("");
}

}  // namespace
}  // namespace geardyn::analyses
