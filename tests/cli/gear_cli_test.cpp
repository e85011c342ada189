// The gear mesh-excitation chain through the geardyn program: a model file with only a gear
// pair runs gear_pair, mesh_force, mesh_harmonics and correlation (exit 0, every analysis ok,
// the tooth force of the spur reference pair in tooth_forces.csv), and a pair whose contact
// ratio is below 1 is bad input (exit 2) found before any analysis runs or any result is written.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli/cli_support.hpp"

namespace {

using namespace geardyn::cli_test;

const std::string kModel = R"(version = 1
title = "spur pair, mesh excitation chain"
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
inertia1 = 2e-4
inertia2 = 3e-3
[[analyses]]
name = "pair"
type = "gear_pair"
[[analyses]]
name = "force"
type = "mesh_force"
speed_start_rpm = 2000
speed_stop_rpm = 30000
speed_count = 15
detail_rpm = [10000]
[[analyses]]
name = "harmonics"
type = "mesh_harmonics"
speed_rpm = 6000
nodal_diameters = [0, 2, 5]
[[analyses]]
name = "torque_variant"
type = "gear_pair"
set = ["gear_pairs[0].torque=200"]
[[analyses]]
name = "measured"
type = "correlation"
measured_file = "measured.csv"
)";

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// F_t = T / r = 100 N m / 0.030 m (spur, docs/theory.md §11.2); 1e-6 N: the CSV's printed digits.
TEST(GearanCli, GearOnlyModelRunsTheWholeChain) {
  const fs::path dir = fresh_dir("gearan_chain");
  write(dir / "in" / "model.toml", kModel);
  std::string csv = "speed_rpm, amplitude_ustrain\n";
  for (int i = 0; i <= 200; ++i) {
    const double r = (2000.0 + 20.0 * i) / 4000.0;
    csv += std::to_string(2000.0 + 20.0 * i) + ", " +
           std::to_string(1.0 / std::sqrt(std::pow(1 - r * r, 2) + std::pow(0.04 * r, 2))) + "\n";
  }
  write(dir / "in" / "measured.csv", csv);
  const ProcessResult r =
      run("run -q " + (dir / "in" / "model.toml").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto manifest = read_json(dir / "out" / "manifest.json");
  EXPECT_EQ(manifest["status"], "ok");
  EXPECT_EQ(manifest["analyses"].size(), 5u);
  for (const auto& a : manifest["analyses"]) EXPECT_EQ(a["status"], "ok") << a["name"];

  auto forces = read_csv(dir / "out" / "pair" / "tooth_forces.csv");
  ASSERT_FALSE(forces["tangential_force_n"].empty());
  EXPECT_NEAR(std::stod(forces["tangential_force_n"][0]), 3333.333333, 1e-6);
  auto variant = read_csv(dir / "out" / "torque_variant" / "tooth_forces.csv");
  EXPECT_NEAR(std::stod(variant["tangential_force_n"][0]), 6666.666667, 1e-6);
  auto sweep = read_csv(dir / "out" / "force" / "sweep_up.csv");
  EXPECT_EQ(sweep["speed_rpm"].size(), 15u);
  auto harmonics = read_csv(dir / "out" / "harmonics" / "harmonics.csv");
  EXPECT_EQ(harmonics["engine_order"].size(), 6u);
  EXPECT_TRUE(fs::exists(dir / "out" / "measured" / "peaks.csv"));
  EXPECT_TRUE(fs::exists(dir / "out" / "report.html"));
}

TEST(GearanCli, ContactRatioBelowOneIsBadInputBeforeAnyResult) {
  const fs::path dir = fresh_dir("gearan_bad_pair");
  std::string model = kModel;
  model.replace(model.find("torque = 100"), 12, "torque = 100\naddendum_coefficient = 0.5");
  write(dir / "in" / "model.toml", model);
  write(dir / "in" / "measured.csv", "speed_rpm, amplitude_m\n1,1\n2,2\n3,3\n4,2\n5,1\n");
  const ProcessResult check = run("check " + (dir / "in" / "model.toml").string());
  EXPECT_EQ(check.exit_code, 2) << check.out << check.err;
  EXPECT_NE(check.err.find("gear_pairs[0]"), std::string::npos) << check.err;
  EXPECT_NE(check.err.find("contact ratio"), std::string::npos) << check.err;
  const ProcessResult r =
      run("run -q " + (dir / "in" / "model.toml").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
