// examples/spur_tip_relief: the loaded tooth contact analysis of a relieved spur pair runs, and
// the numbers its README states hold: the TE peak-to-peak over torque has its minimum inside
// the range near the relief's design load (the Harris map: S.L. Harris, "Dynamic loads on the
// teeth of spur gears", Proc. IMechE 172, 1958), and the face-load factor falls with the load.
// The README quotes three significant digits; the tolerances are half a unit of the last one.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/example_runs.hpp"

namespace {

using namespace geardyn::cli_test;

TEST(SpurTipReliefExample, RunsAndShowsTheHarrisMapMinimum) {
  ProcessResult r;
  const fs::path out = run_example("spur_tip_relief", r);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto manifest = read_json(out / "manifest.json");
  EXPECT_EQ(manifest["status"], "ok");

  auto summary = read_csv(out / "harris_map" / "summary.csv");
  const auto torque = numbers(summary["torque_nm"]);
  const auto pp = numbers(summary["te_peak_peak_m"]);
  const auto khb = numbers(summary["face_load_factor"]);
  ASSERT_EQ(torque.size(), 10u);
  const auto best = static_cast<std::size_t>(std::min_element(pp.begin(), pp.end()) - pp.begin());
  EXPECT_EQ(torque[best], 60.0);
  EXPECT_NEAR(pp[best], 1.03e-6, 0.005e-6);
  EXPECT_NEAR(pp[0], 3.39e-6, 0.005e-6);
  EXPECT_NEAR(pp[9], 8.03e-6, 0.005e-6);
  EXPECT_NEAR(khb[0], 2.12, 0.005);
  EXPECT_NEAR(khb[9], 1.22, 0.005);
  for (std::size_t i = 1; i < khb.size(); ++i) EXPECT_LT(khb[i], khb[i - 1]);

  auto harmonics = read_csv(out / "harris_map" / "te_harmonics.csv");
  const auto t = numbers(harmonics["torque_nm"]), order = numbers(harmonics["mesh_order"]);
  const auto amp = numbers(harmonics["amplitude_0_peak_m"]);
  bool found = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] != 100.0 || order[i] != 1.0) continue;
    EXPECT_NEAR(amp[i], 0.847e-6, 0.0005e-6);
    found = true;
  }
  EXPECT_TRUE(found);
}

}  // namespace
