// order_analysis through the geardyn program: a bad record gives a located error (the record
// file's line where it applies) and exit code 2 from both `geardyn check` and `geardyn run`, with
// no results folder left behind; a good record runs and writes the order tables.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli_support.hpp"

namespace geardyn::cli_test {
namespace {

// 2 s at 2 kHz of a shaft at 600 rpm (angle column), a tacho at 1 pulse/rev and a signal with
// order 5. `bad_row` >= 0: that row's time goes back by 2 samples.
void write_record(const fs::path& path, int bad_row, bool flat_tacho) {
  std::ofstream out(path);
  out.precision(17);
  out << "time_s,angle_rad,tacho_v,acc_m_per_s2\n";
  for (int j = 0; j < 4000; ++j) {
    const double t = (j == bad_row ? j - 2 : j) / 2000.0;
    const double th = kTwoPi * 10.0 * t;
    out << t << ',' << th << ',' << (flat_tacho ? 0.0 : std::cos(th)) << ',' << std::sin(5 * th)
        << '\n';
  }
}

void write_model(const fs::path& dir, const std::string& keys) {
  std::ofstream(dir / "model.toml") << "version = 1\n"
                                       "[[analyses]]\nname = \"orders\"\n"
                                       "type = \"order_analysis\"\nrecord_file = \"record.csv\"\n"
                                    << keys;
}

struct Case {
  std::string name, keys, expect;
  int bad_row = -1;
  bool flat_tacho = false;
  bool no_file = false;
};

TEST(OrderAnalysisCli, BadRecordsExitWithCodeTwoAndALocatedMessage) {
  const std::string angle = "angle_column = \"angle_rad\"\norders = [5]\nblock_length = 256\n";
  const std::vector<Case> cases = {
      {"missing_file", angle, "analyses[0].record_file", -1, false, true},
      {"missing_column", "angle_column = \"theta\"\norders = [5]\n", "analyses[0].angle_column"},
      {"time_back", angle, "record.csv:102:", 100},
      {"no_pulses", "tacho_column = \"tacho_v\"\norders = [5]\n", "analyses[0].tacho_column", -1,
       true},
      {"speed_range", angle + "speed_range_rpm = [1000, 2000]\n", "600.0 .. 600.0 rpm"},
  };
  for (const Case& c : cases) {
    const fs::path dir = fresh_dir("order_analysis_" + c.name);
    fs::create_directories(dir);
    if (!c.no_file) write_record(dir / "record.csv", c.bad_row, c.flat_tacho);
    write_model(dir, c.keys);
    for (const char* command : {"check ", "run -q "}) {
      const std::string out_dir = (dir / "results").string();
      const ProcessResult r = run(std::string(command) + (dir / "model.toml").string() +
                                  (command[0] == 'r' ? " -o " + out_dir : ""));
      EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
      EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << ": " << r.err;
      EXPECT_FALSE(fs::exists(dir / "results" / "orders")) << c.name;
    }
  }
}

TEST(OrderAnalysisCli, GoodRecordWritesTheOrderTables) {
  const fs::path dir = fresh_dir("order_analysis_good");
  fs::create_directories(dir);
  write_record(dir / "record.csv", -1, false);
  write_model(dir,
              "tacho_column = \"tacho_v\"\norders = [5]\nblock_length = 256\n"
              "channels = [\"acc_m_per_s2\"]\n");
  const ProcessResult r =
      run("run -q " + (dir / "model.toml").string() + " -o " + (dir / "results").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto cuts = read_csv(dir / "results" / "orders" / "order_cuts.csv");
  ASSERT_TRUE(cuts.count("order_5_acc_m_per_s2"));
  // Amplitude 1 at 600 rpm (order 5 = 50 Hz, 40 samples per cycle): within 1 % (issue #17).
  for (const std::string& a : cuts.at("order_5_acc_m_per_s2")) EXPECT_NEAR(std::stod(a), 1.0, 0.01);
  for (const char* f : {"waterfall_acc_m_per_s2.csv", "levels.csv", "third_octave.csv", "psd.csv"})
    EXPECT_TRUE(fs::exists(dir / "results" / "orders" / f)) << f;
}

}  // namespace
}  // namespace geardyn::cli_test
