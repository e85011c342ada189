// The cost of a transient is estimated from its settings before it runs, and refused at check
// time above the limits (TransientCost: 1e8 steps, a 2 GB time history) with an InputError at
// the analysis key that names duration, time_step, output_every and the estimate. The estimate
// itself is counting: steps = ceil(duration / time_step), stored samples = floor(steps /
// output_every) + 1, columns = time, speed and one per sensor.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::analyses {
namespace {

namespace fs = std::filesystem;

TEST(TransientCost, CountsStepsSamplesAndBytes) {
  TransientSettings s;
  s.duration = 0.3;
  s.time_step = 1e-4;  // 0.3 / 1e-4 = 2999.9999999999995: 3000 steps
  s.output_every = 7;
  const TransientCost c = estimate_cost(s, 4);
  EXPECT_EQ(c.steps, 3000.0);
  EXPECT_EQ(c.samples, 428.0 + 1.0);  // floor(3000 / 7) + t = 0
  EXPECT_EQ(c.columns, 6);
  EXPECT_DOUBLE_EQ(c.csv_bytes, 429.0 * 6 * TransientCost::kBytesPerValue);
  EXPECT_TRUE(c.excess().empty());
  s.duration = 1e4 + 1.0;  // 1.0001e8 steps
  EXPECT_NE(estimate_cost(s, 4).excess().find("time steps"), std::string::npos);
}

std::string demo_with_transient(const std::string& duration, const std::string& step,
                                const std::string& every) {
  const fs::path file =
      fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml";
  // The demo without its analyses' `set` variants (a variant's check reports any analysis's
  // error at its own `set` key).
  std::ifstream in(file);
  std::string text, line;
  while (std::getline(in, line))
    if (line.rfind("set = ", 0) != 0) text += line + "\n";
  return text + "\n[[analyses]]\nname = \"long\"\ntype = \"transient\"\nspeed_rpm = 36900\n" +
         "duration = " + duration + "\ntime_step = " + step + "\noutput_every = " + every + "\n";
}

TEST(TransientCost, TooLargeARecordIsRefusedAtCheckTimeWithTheEstimate) {
  // 1e8 steps (the size the robustness issue saw accepted), every one stored with the demo's
  // 4 sensors: 1e8 x 6 x 24 B = 14.4 GB.
  try {
    parse_model(demo_with_transient("10", "1e-7", "1"), "model.toml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.key_path().find("output_every"), std::string::npos) << e.key_path();
    EXPECT_GT(e.where().line, 0);
    EXPECT_NE(e.found().find("duration = 10 s"), std::string::npos) << e.found();
    EXPECT_NE(e.found().find("time_step = 1e-07 s"), std::string::npos) << e.found();
    EXPECT_NE(e.found().find("output_every = 1"), std::string::npos) << e.found();
    EXPECT_NE(e.found().find("14.4 GB"), std::string::npos) << e.found();
    EXPECT_NE(e.expected().find("2 GB"), std::string::npos) << e.expected();
  }
  // More than 1e8 steps, however few are stored: at time_step.
  try {
    parse_model(demo_with_transient("20", "1e-7", "100000"), "model.toml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.key_path().find("time_step"), std::string::npos) << e.key_path();
    EXPECT_NE(e.found().find("2e+08 steps"), std::string::npos) << e.found();
  }
  // The same steps stored every 100th: 1e6 samples, 144 MB: accepted.
  EXPECT_NO_THROW(parse_model(demo_with_transient("10", "1e-7", "100"), "model.toml"));
}

}  // namespace
}  // namespace geardyn::analyses
