// examples/ptu_runup: a power transfer unit (a 13/39 hypoid pair on shafts in preloaded
// taper-roller bearings, a reduced housing and cover plate joined by six preloaded bolts with a
// tightening sequence) run up from rest to 3000 rpm, and a bolt-stiffness sweep. The checks are
// the README's key numbers, each against a closed form:
// - static torque balance of a frictionless gear pair (virtual work): T_pinion = T_wheel z1 / z2;
// - kinematics at the 3000 rpm hold: wheel speed = pinion speed z1 / z2; the DTE's largest
//   spectral line at the mesh frequency z1 n / 60 (H. N. Oezguven and D. R. Houser, "Mathematical
//   models used in gear dynamics - a review", J. Sound Vib. 121, 1988); the bolt force's largest
//   line at the pinion bearings' outer-race ball-pass frequency BPFO = Z (1 - D cos(alpha) / d_m)
//   f_shaft / 2 (T. A. Harris, "Rolling Bearing Analysis", 4th ed., 2001);
// - the VDI 2230 joint diagram (VDI 2230 Part 1, "Systematic calculation of highly stressed
//   bolted joints", 2015) with load introduction n = 1: with the joint closed the bolt takes
//   the share Phi = k_S / (k_S + k_P) of the external axial load F_A = F_S - F_P, i.e.
//   F_S - F_V = Phi (F_S - F_P), in every sample of the run after the tightening and at every
//   point of the sweep; with the external load compressive (F_A < 0) a stiffer bolt carries
//   less force;
// - the FRF at the operating point by modal superposition (docs/theory.md §16.14): every
//   sensor's largest accelerance peak sits at a natural frequency of the eigen table (a lightly
//   damped mode's peak is within zeta^2 of it: D. J. Ewins, "Modal Testing", 2000, §2.2), and
//   the sum agrees with the direct solve where it should (its own notes); bad FRF keys are
//   located errors (exit code 2);
// - the order analysis of the run-up (order_channels): block speeds against the driver's ramp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "support/example_runs.hpp"

namespace {

using namespace geardyn::cli_test;

constexpr double kPreload = 15000.0;       // N, bolts[*].preload
constexpr double kClamp = 2.5e8;           // N/m, bolts[*].clamp_stiffness
constexpr double kBolt = 5.0e7;            // N/m, bolts[*].bolt_stiffness of the run-up
constexpr double kTightened = 0.068;       // s: the last bolt's activation 0.06 s + ramp 8 ms
constexpr double kHoldStart = 0.28;        // s: the 3000 rpm hold (spectrum_start)
constexpr double kBinHz = 5000.0 / 251.0;  // the spectra's resolution: 251 samples at 5 kHz

using Csv = std::map<std::string, std::vector<std::string>>;

// A column as numbers (strtod: the written subnormals, e.g. a held speed of 5e-318 rpm, are
// numbers too, where std::stod throws out_of_range); a missing column or a cell that is no
// number is a failure naming it.
std::vector<double> col(Csv& table, const std::string& name) {
  EXPECT_TRUE(table.count(name)) << "no column " << name;
  std::vector<double> v;
  for (const std::string& c : table[name]) {
    char* end = nullptr;
    v.push_back(std::strtod(c.c_str(), &end));
    if (c.empty() || end != c.c_str() + c.size())
      ADD_FAILURE() << "column " << name << ": '" << c << "' is no number";
  }
  return v;
}

// The frequency of the largest amplitude above 100 Hz (below it: the run-up's leakage).
double dominant_hz(const std::vector<double>& f, const std::vector<double>& a) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f[i] > 100.0 && (f[best] <= 100.0 || a[i] > a[best])) best = i;
  return f[best];
}

// VDI 2230 joint diagram, closed joint, n = 1: F_S - F_V = Phi (F_S - F_P). The element
// computes both forces from one opening u (F_S = F_V + k_S u, F_P = F_V - k_P u), so the
// identity holds to rounding: 1e-9 of the preload (observed: 1e-16 relative).
void expect_joint_diagram(double bolt, double clamp, double k_bolt, const std::string& where) {
  const double phi = k_bolt / (k_bolt + kClamp);
  EXPECT_NEAR(bolt - kPreload, phi * (bolt - clamp), 1e-9 * kPreload) << where;
}

void check_runup(const fs::path& dir) {
  // Static equilibrium (pinion held, 300 N m on the wheel): the holding torque is the wheel
  // torque x z1 / z2 = 100 N m; the Newton residual (|r| < 1.1e-5 N) bounds the error far
  // below 1e-6 N m.
  auto st = read_csv(dir / "static_equilibrium.csv");
  bool held = false;
  for (std::size_t i = 0; i < st["element"].size(); ++i)
    if (st["element"][i] == "driver 'input'" && st["quantity"][i] == "holding torque") {
      held = true;
      EXPECT_NEAR(std::stod(st["value"][i]), 100.0, 1e-6);
    }
  EXPECT_TRUE(held);

  auto th = read_csv(dir / "time_history.csv");
  const auto t = col(th, "time_s");
  const auto out_rpm = col(th, "output_speed_rpm");
  const auto in_rpm = col(th, "input_speed_rpm");
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= kHoldStart - 1e-9) {
      EXPECT_NEAR(in_rpm[i], 3000.0, 0.1) << t[i];  // the speed driver's table
      sum += out_rpm[i];
      ++n;
    }
  ASSERT_EQ(n, 251);
  // Mean wheel speed over the hold = 3000 x 13 / 39. The DTE ripple swings it by +-2 rpm at the
  // mesh frequency (650 Hz, about 32 cycles in the 50 ms window): an incomplete cycle leaves at
  // most amplitude / cycles = 0.06 rpm in the mean.
  EXPECT_NEAR(sum / n, 1000.0, 0.1);

  // The joint diagram in every sample once all bolts are tight and closed.
  int checked = 0;
  for (int b = 1; b <= 6; ++b) {
    const auto fs_ = col(th, "bolt" + std::to_string(b) + "_bolt_force_n");
    const auto fp = col(th, "bolt" + std::to_string(b) + "_clamp_force_n");
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= kTightened && fp[i] > 0.0) {
        expect_joint_diagram(fs_[i], fp[i], kBolt, "bolt " + std::to_string(b));
        ++checked;
      }
  }
  EXPECT_GT(checked, 6 * 1300);

  auto sp = read_csv(dir / "spectrum.csv");
  const auto f = col(sp, "frequency_hz");
  // The DTE's largest line: the mesh frequency 13 x 3000 / 60 = 650 Hz, within one bin.
  EXPECT_NEAR(dominant_hz(f, col(sp, "hypoid_dte_m")), 650.0, kBinHz);
  // Bolt 1's force: the pinion bearings' BPFO, 16 rollers, D = 8 mm, d_m = 50 mm, 15 deg, at
  // 50 Hz: 16 x 50 x (1 - 0.008 cos 15 / 0.05) / 2 = 338.2 Hz, within one bin.
  const double bpfo =
      16.0 * 50.0 * (1.0 - 0.008 * std::cos(15.0 * std::numbers::pi / 180.0) / 0.05) / 2.0;
  EXPECT_NEAR(dominant_hz(f, col(sp, "bolt1_bolt_force_n")), bpfo, kBinHz);

  // The tightened, assembled state at rest: bolt 1's force, mean over 70-80 ms (pinion still
  // held), equals the static value of the sweep at k_S = 5e7 N/m (14831.2 N) up to the ringing
  // the tightening leaves (+-35 N peaks, lightly damped cover modes): 20 N.
  const auto f1 = col(th, "bolt1_bolt_force_n");
  double m = 0.0;
  int k = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= 0.07 - 1e-9 && t[i] <= 0.08 + 1e-9) {
      m += f1[i];
      ++k;
    }
  EXPECT_NEAR(m / k, 14831.2, 20.0);
}

void check_sweep(const fs::path& dir) {
  auto sw = read_csv(dir / "sweep.csv");
  const auto k = col(sw, "value_N_m");
  ASSERT_EQ(k.size(), 4u);
  const auto s1 = col(sw, "channel_peak_bolt1_bolt_force_n_N");
  const auto p1 = col(sw, "channel_peak_bolt1_clamp_force_n_N");
  const auto s4 = col(sw, "channel_peak_bolt4_bolt_force_n_N");
  const auto p4 = col(sw, "channel_peak_bolt4_clamp_force_n_N");
  const auto seat = col(sw, "channel_peak_wheel_c_fz_n_N");
  for (std::size_t i = 0; i < k.size(); ++i) {
    EXPECT_EQ(sw["status"][i], "ok");
    expect_joint_diagram(s1[i], p1[i], k[i], "bolt 1, k_S " + std::to_string(k[i]));
    expect_joint_diagram(s4[i], p4[i], k[i], "bolt 4, k_S " + std::to_string(k[i]));
    EXPECT_LT(s1[i] - p1[i], 0.0);  // F_A < 0: the cover's bearing load presses the joint
    EXPECT_LT(s4[i] - p4[i], 0.0);
    if (i > 0) {
      EXPECT_LT(s1[i], s1[i - 1]);  // a stiffer bolt takes more of the compressive F_A
      EXPECT_LT(s4[i], s4[i - 1]);
      EXPECT_GT(seat[i], seat[i - 1]);  // a stiffer cover mount: its bearing carries more
    }
  }
  // The README's numbers at k_S = 5e7 N/m (the run-up's bolts): 14831.2 N and 15844.2 N.
  EXPECT_NEAR(s1[1], 14831.2, 0.05);
  EXPECT_NEAR(p1[1], 15844.2, 0.05);
}

// The FRF (accelerance of every sensor to a unit hypoid mesh force, 50-2000 Hz in 5 Hz steps,
// 40 modes with the static correction).
void check_frf(const fs::path& out) {
  const fs::path dir = out / "runup";
  auto eig = read_csv(dir / "eigen.csv");
  const auto fn = col(eig, "undamped_natural_frequency_hz");
  ASSERT_EQ(fn.size(), 40u);
  auto frf = read_csv(dir / "frf.csv");
  const auto f = col(frf, "frequency_hz");
  ASSERT_EQ(f.size(), 391u);
  // The largest peak of each sensor lies at a mode of the eigen table: within one grid step
  // (5 Hz; the modes' damping ratios below 0.03 shift a peak by less than zeta^2 f_n = 2 Hz).
  // README: seat_pinion 0.497 m/s^2/N at 1815 Hz (mode 18, 1812.8 Hz), seat_wheel_housing
  // 0.454 m/s^2/N at 1805 Hz (mode 17, 1806.0 Hz).
  const std::map<std::string, std::pair<double, double>> readme = {
      {"seat_pinion", {1815.0, 0.497}}, {"seat_wheel_housing", {1805.0, 0.454}}};
  for (const std::string s : {"seat_wheel_housing", "seat_wheel_cover", "seat_pinion",
                              "seat_pinion_y", "bolt1_cover", "bolt2_cover"}) {
    const auto a = col(frf, s + "_m_per_s2_per_n");
    ASSERT_EQ(a.size(), f.size());
    const auto top = std::max_element(a.begin(), a.end()) - a.begin();
    const double f_peak = f[static_cast<std::size_t>(top)];
    double nearest = 1e300;
    for (double x : fn) nearest = std::min(nearest, std::abs(x - f_peak));
    EXPECT_LE(nearest, 5.0) << s << " peak at " << f_peak << " Hz";
    if (readme.count(s)) {
      EXPECT_NEAR(f_peak, readme.at(s).first, 1e-6) << s;
      EXPECT_NEAR(a[static_cast<std::size_t>(top)], readme.at(s).second,
                  0.005 * readme.at(s).second)
          << s;
    }
  }
  // The notes' check against the direct solve: at the first mode (222.4 Hz) the truncated modes
  // leave 4.6e-5 of the largest value, at the band's top 2.8e-2 (README).
  bool first = false, top = false;
  for (const std::string& n : notes_of(out, "runup")) {
    const auto at = n.find("largest deviation ");
    if (n.rfind("FRF check", 0) != 0 || at == std::string::npos) continue;
    const double dev = std::stod(n.substr(at + 18));
    if (n.find(" at 222.4") != std::string::npos) {
      first = true;
      EXPECT_LT(dev, 1e-3) << n;
    }
    if (n.find(" at 2000 Hz") != std::string::npos) {
      top = true;
      EXPECT_LT(dev, 0.05) << n;
    }
  }
  EXPECT_TRUE(first && top);
  // The orbit of the pinion seat (two sensors on seat_p1, z and y) is in the report.
  std::ifstream report(out / "report.html");
  std::stringstream html;
  html << report.rdbuf();
  EXPECT_NE(html.str().find("orbit_seat_pinion_m_seat_pinion_y_m"), std::string::npos);
}

// The order analysis of the wheel-seat acceleration (order_channels): each one-revolution
// block's mean speed is the driver's speed at the block's middle (exact for a linear ramp and a
// hold; the block across the ramp's end at 0.28 s is skipped), and the README's largest order
// cuts (this model's numbers: no closed form, held to 2 %).
void check_order_analysis(const fs::path& dir) {
  Csv cuts = read_csv(dir / "order_cuts.csv");
  const std::vector<double> t = col(cuts, "time_s");
  const std::vector<double> n = col(cuts, "speed_rpm");
  const std::vector<double> a13 = col(cuts, "order_13_seat_wheel_housing_m_per_s2");
  const std::vector<double> a26 = col(cuts, "order_26_seat_wheel_housing_m_per_s2");
  ASSERT_EQ(n.size(), 14u);
  int checked = 0;
  for (std::size_t b = 0; b < n.size(); ++b) {
    const double half = 30.0 / n[b];  // half a revolution [s]
    if (t[b] + half < kHoldStart || t[b] - half > kHoldStart) {
      const double ramp = 3000.0 * std::clamp((t[b] - 0.08) / 0.2, 0.0, 1.0);
      EXPECT_NEAR(n[b], ramp, 0.1) << t[b];
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12);  // two blocks touch the ramp's end at 0.28 s
  const auto i13 = std::max_element(a13.begin(), a13.end()) - a13.begin();
  EXPECT_NEAR(a13[static_cast<std::size_t>(i13)], 14.27, 0.02 * 14.27);
  EXPECT_NEAR(n[static_cast<std::size_t>(i13)], 1618.0, 1.0);
  const auto i26 = std::max_element(a26.begin(), a26.end()) - a26.begin();
  EXPECT_NEAR(a26[static_cast<std::size_t>(i26)], 6.64, 0.02 * 6.64);
  EXPECT_NEAR(n[static_cast<std::size_t>(i26)], 668.0, 1.0);
  for (const char* f : {"waterfall_seat_wheel_housing_m_per_s2.csv", "levels.csv",
                        "third_octave.csv", "psd.csv", "order_map_seat_wheel_housing_m_per_s2.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
}

TEST(PtuRunupExample, RunUpAndBoltStiffnessSweepGiveTheReadmeNumbers) {
  ProcessResult r;
  const fs::path out = run_example("ptu_runup", r);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(read_json(out / "manifest.json")["status"], "ok");
  check_runup(out / "runup");
  check_sweep(out / "bolt_stiffness_sweep");
  check_frf(out);
  check_order_analysis(out / "runup");
}

// Bad FRF keys: a located error and exit code 2 from `geardyn check`, in the file (line of the
// key) and through --set.
TEST(PtuRunupExample, BadFrfKeysAreLocatedErrors) {
  const fs::path dir = fresh_dir("ptu_runup_bad_frf");
  fs::create_directories(dir);
  for (const char* deck : {"housing.bdf", "cover.bdf"})
    fs::copy_file(fs::path(kSource) / "examples/ptu_runup" / deck, dir / deck);
  std::ifstream in(fs::path(kSource) / "examples/ptu_runup/model.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string model = text.str();
  const std::string key = "frf_excitation = \"hypoid\"";
  const auto at = model.find(key);
  ASSERT_NE(at, std::string::npos);
  const auto line = std::count(model.begin(), model.begin() + static_cast<long>(at), '\n') + 1;
  model.replace(at, key.size(), "frf_excitation = \"nowhere\"");
  std::ofstream(dir / "model.toml") << model;
  ProcessResult r = run("check " + (dir / "model.toml").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("model.toml:" + std::to_string(line) + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("analyses[0].frf_excitation"), std::string::npos) << r.err;

  const std::string source = kSource + "/examples/ptu_runup/model.toml";
  for (const auto& [set, key_path] : std::vector<std::pair<std::string, std::string>>{
           {"analyses[0].frf_band_hz=[2000.0, 50.0]", "frf_band_hz"},  // f_min >= f_max
           {"analyses[0].frf_band_hz=[100.0, 100.0]", "frf_band_hz"},  // empty band
           {"analyses[0].frf_band_hz=[100.0]", "frf_band_hz"},         // one value
           {"analyses[0].frf_modes=41", "frf_modes"}}) {               // above modes = 40
    r = run("check " + source + " --set '" + set + "'");
    EXPECT_EQ(r.exit_code, 2) << set << ": " << r.err;
    EXPECT_NE(r.err.find("analyses[0]." + key_path), std::string::npos) << set << ": " << r.err;
  }
}

}  // namespace
