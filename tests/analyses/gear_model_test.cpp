// The [[gear_pairs]] section and the gear analyses in the model file: every key read into the
// Model in SI units (good input), and every class of bad input reported as an InputError naming
// file:line, the key path, what was expected and what was found — at parse time, or (geometry,
// STE and measured files, which need the gear library) by analyses::check_inputs before
// any analysis runs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/gear_pair.hpp"
#include "geardyn/analyses/mesh_force.hpp"
#include "geardyn/analyses/mesh_harmonics.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/gear/ste.hpp"
#include "geardyn/model/parse.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kRpm = 2.0 * std::numbers::pi / 60.0;

const std::string kMaterial = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
)";

const std::string kSpur = R"([[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
)";

TEST(GearanModel, EveryGearPairKeyIsReadInSi) {
  const fs::path dir = fresh_dir("every_key");
  write_file(dir / "ste.csv",
             "angle_deg, ste_um@100Nm, ste_um@300Nm\n0, 2, 5\n5, 3, 7\n10, 2.5, 6\n");
  const model::Model m = load(dir, kMaterial + R"([[gear_pairs]]
name = "stage1"
type = "helical"
internal = true
teeth1 = 23
teeth2 = 71
module = 0.0025
pressure_angle_deg = 17.5
helix_angle_deg = 15
hand = "left"
face_width = 0.03
profile_shift1 = 0.2
profile_shift2 = 0.1
addendum_coefficient = 0.9
dedendum_coefficient = 1.3
centre_distance = 0.062
torque = 250
inertia1 = 0.01
inertia2 = inf
material1 = "steel"
material2 = "steel"
stiffness_correction = 0.9
application_factor = 1.25
load_correction = false
rim_thickness = 0.01
web_thickness = 0.012
ste_file = "ste.csv"
ste_interpolation = "hold"
ste_extrapolation = true
ste_shift = 0.25
ste_samples = 64
mesh_damping_ratio = 0.05
backlash = 1e-4
[[gear_pairs]]
name = "bevel"
type = "hypoid"
teeth1 = 11
teeth2 = 41
module = 0.005
helix_angle_deg = 30
pinion_spiral_angle_deg = 45
rotation = "ccw"
face_width = 0.035
shaft_angle_deg = 85
outer_cone_distance = 0.105
torque = 300
)");
  ASSERT_EQ(m.gear_pairs.size(), 2u);
  const model::GearPair& g = m.gear_pairs[0];
  EXPECT_EQ(g.name, "stage1");
  EXPECT_EQ(g.type, model::GearType::Helical);
  EXPECT_TRUE(g.internal);
  EXPECT_EQ(g.teeth1, 23);
  EXPECT_EQ(g.teeth2, 71);
  EXPECT_DOUBLE_EQ(g.module, 0.0025);
  EXPECT_DOUBLE_EQ(g.pressure_angle, 17.5 * kDeg);
  EXPECT_DOUBLE_EQ(g.helix_angle, 15 * kDeg);
  EXPECT_EQ(g.hand, model::Hand::Left);
  EXPECT_DOUBLE_EQ(g.face_width, 0.03);
  EXPECT_DOUBLE_EQ(g.profile_shift1, 0.2);
  EXPECT_DOUBLE_EQ(g.profile_shift2, 0.1);
  EXPECT_DOUBLE_EQ(g.addendum_coefficient, 0.9);
  EXPECT_DOUBLE_EQ(g.dedendum_coefficient, 1.3);
  EXPECT_DOUBLE_EQ(g.centre_distance, 0.062);
  EXPECT_DOUBLE_EQ(g.torque, 250.0);
  EXPECT_DOUBLE_EQ(g.inertia1, 0.01);
  EXPECT_TRUE(std::isinf(g.inertia2));
  EXPECT_EQ(g.material1, "steel");
  EXPECT_EQ(g.material2, "steel");
  EXPECT_DOUBLE_EQ(g.stiffness_correction, 0.9);
  EXPECT_DOUBLE_EQ(g.application_factor, 1.25);
  EXPECT_FALSE(g.load_correction);
  EXPECT_DOUBLE_EQ(g.rim_thickness, 0.01);
  EXPECT_DOUBLE_EQ(g.web_thickness, 0.012);
  EXPECT_EQ(g.ste_file, "ste.csv");
  EXPECT_EQ(g.ste_interpolation, model::SteInterpolationKind::Hold);
  EXPECT_TRUE(g.ste_extrapolation);
  EXPECT_DOUBLE_EQ(g.ste_shift, 0.25);
  EXPECT_EQ(g.ste_samples, 64);
  EXPECT_DOUBLE_EQ(g.mesh_damping_ratio, 0.05);
  EXPECT_DOUBLE_EQ(g.backlash, 1e-4);

  const model::GearPair& h = m.gear_pairs[1];
  EXPECT_EQ(h.type, model::GearType::Hypoid);
  EXPECT_DOUBLE_EQ(h.pinion_spiral_angle, 45 * kDeg);
  EXPECT_EQ(h.rotation, model::GearRotation::CounterClockwise);
  EXPECT_DOUBLE_EQ(h.shaft_angle, 85 * kDeg);
  EXPECT_DOUBLE_EQ(h.outer_cone_distance, 0.105);
  // Defaults.
  EXPECT_FALSE(h.internal);
  EXPECT_DOUBLE_EQ(h.pressure_angle, 20 * kDeg);
  EXPECT_EQ(h.hand, model::Hand::Right);
  EXPECT_DOUBLE_EQ(h.addendum_coefficient, 1.0);
  EXPECT_DOUBLE_EQ(h.dedendum_coefficient, 1.25);
  EXPECT_DOUBLE_EQ(h.mesh_damping_ratio, 0.08);
  EXPECT_TRUE(h.load_correction);
  EXPECT_TRUE(h.ste_file.empty());
  EXPECT_TRUE(std::isnan(h.backlash));
  EXPECT_TRUE(std::isnan(h.inertia1));
}

TEST(GearanModel, EveryGearAnalysisKeyIsReadInSi) {
  const fs::path dir = fresh_dir("analysis_keys");
  write_file(dir / "measured.csv", "speed_rpm, amplitude_um\n1,1\n2,2\n3,5\n4,2\n5,1\n");
  const model::Model m = load(dir, kMaterial + kSpur + R"(inertia1 = 0.001
inertia2 = 0.004
[[analyses]]
name = "pair"
type = "gear_pair"
pair = "spur"
[[analyses]]
name = "force"
type = "mesh_force"
speed_start_rpm = 100
speed_stop_rpm = 1000
speed_count = 4
direction = "down"
model = "infinite_inertia"
contact_loss = false
detail_rpm = [200, 300]
[[analyses]]
name = "force_list"
type = "mesh_force"
speed_rpm = [100, 200]
[[analyses]]
name = "harmonics"
type = "mesh_harmonics"
speed_rpm = 3000
gear = 2
window_shift = -0.5
contact_ratio = 1.5
nodal_diameters = [0, 3, 20]
orders_per_diameter = 4
max_order = 90
[[analyses]]
name = "corr"
type = "correlation"
measured_file = "measured.csv"
min_prominence_db = 3
max_peaks = 2
reference_peak_rpm = 3100
reference_amplitude = 4e-6
reference_q = 20
)");
  ASSERT_EQ(m.analyses.size(), 5u);
  EXPECT_EQ(m.analyses[0].settings_of<analyses::GearPairSettings>().pair, "spur");

  const auto& f = m.analyses[1].settings_of<analyses::MeshForceSettings>();
  EXPECT_TRUE(f.pair.empty());
  ASSERT_EQ(f.speeds.size(), 4u);
  EXPECT_NEAR(f.speeds[0], 100 * kRpm, 1e-12);
  EXPECT_NEAR(f.speeds[3], 1000 * kRpm, 1e-12);
  EXPECT_NEAR(f.speeds[1], 400 * kRpm, 1e-12);
  EXPECT_EQ(f.direction, analyses::SweepDirectionKind::Down);
  EXPECT_EQ(f.model, analyses::MeshForceModel::InfiniteInertia);
  EXPECT_FALSE(f.contact_loss);
  ASSERT_EQ(f.detail_speeds.size(), 2u);
  EXPECT_NEAR(f.detail_speeds[1], 300 * kRpm, 1e-12);

  const auto& fl = m.analyses[2].settings_of<analyses::MeshForceSettings>();
  ASSERT_EQ(fl.speeds.size(), 2u);
  EXPECT_NEAR(fl.speeds[1], 200 * kRpm, 1e-12);
  EXPECT_EQ(fl.direction, analyses::SweepDirectionKind::Both);
  EXPECT_EQ(fl.model, analyses::MeshForceModel::Dynamic);
  EXPECT_TRUE(fl.contact_loss);

  const auto& h = m.analyses[3].settings_of<analyses::MeshHarmonicsSettings>();
  EXPECT_NEAR(h.speed, 3000 * kRpm, 1e-9);
  EXPECT_EQ(h.gear, 2);
  EXPECT_DOUBLE_EQ(h.window_shift, -0.5);
  EXPECT_DOUBLE_EQ(h.contact_ratio, 1.5);
  EXPECT_EQ(h.nodal_diameters, (std::vector<int>{0, 3, 20}));
  EXPECT_EQ(h.orders_per_diameter, 4);
  EXPECT_EQ(h.max_order, 90);

  const auto& c = m.analyses[4].settings_of<analyses::CorrelationSettings>();
  EXPECT_EQ(c.measured_file, "measured.csv");
  EXPECT_DOUBLE_EQ(c.min_prominence_db, 3.0);
  EXPECT_EQ(c.max_peaks, 2);
  EXPECT_NEAR(c.reference_peak, 3100 * kRpm, 1e-9);
  EXPECT_TRUE(c.reference_is_speed);
  EXPECT_DOUBLE_EQ(c.reference_amplitude, 4e-6);
  EXPECT_DOUBLE_EQ(c.reference_q, 20.0);
  EXPECT_NO_THROW(check_inputs(m, {}));
}

// A step STE held between rows (single / double contact) read onto its own grid keeps every
// row: the grid point j / n equals row j's cycle fraction only up to rounding (1.8 deg x 6 /
// 18 deg), and a Hold curve must not take the previous row's value there (a bug found through
// the Parker reference case: 7 instead of 6 double-contact samples).
TEST(GearanModel, SteFileWithHoldKeepsEveryRow) {
  std::string csv = "angle_deg, ste_um\n";
  for (int j = 0; j < 10; ++j)
    csv += std::to_string(1.8 * j) + ", " + (j < 6 ? "3.125" : "5") + "\n";
  gear::SteReadOptions options;
  options.teeth = 20;
  options.interpolation = gear::SteInterpolation::Hold;
  const gear::SteTable t = gear::parse_ste_csv(csv, "step.csv", options);
  ASSERT_EQ(t.curves.size(), 1u);
  ASSERT_EQ(t.curves[0].size(), 10u);
  for (std::size_t j = 0; j < 10; ++j)
    EXPECT_DOUBLE_EQ(t.curves[0].ste_m()[j], j < 6 ? 3.125e-6 : 5e-6) << "row " << j;
}

// An STE recorded over time at a known speed is the same curve as the one over gear 1's angle:
// 20 teeth at 1000 rpm give a mesh period of 60 / (1000 * 20) s = 3 ms, so rows 0.3 ms apart
// are the rows 1.8 deg apart of the angle file. Equal to round-off (the two abscissas are scaled
// by different periods, 1e-15 relative).
TEST(GearanModel, SteFileWithTimeAbscissaMatchesTheAngleFile) {
  const fs::path dir = fresh_dir("ste_time");
  std::string by_angle = "angle_deg, ste_um\n", by_time = "time_ms, ste_um\n";
  for (int j = 0; j < 10; ++j) {
    const std::string value = std::to_string(3.0 + 0.4 * std::cos(2.0 * std::numbers::pi * j / 10));
    by_angle += std::to_string(1.8 * j) + ", " + value + "\n";
    by_time += std::to_string(0.3 * j) + ", " + value + "\n";
  }
  write_file(dir / "angle.csv", by_angle);
  write_file(dir / "time.csv", by_time);
  const model::Model angle = load(dir, kMaterial + kSpur + "ste_file = \"angle.csv\"\n");
  const model::Model time =
      load(dir, kMaterial + kSpur + "ste_file = \"time.csv\"\nste_speed_rpm = 1000\n");
  EXPECT_NEAR(time.gear_pairs[0].ste_speed, 1000 * kRpm, 1e-12);
  const PairModel a = build_pair_model(angle, 0), t = build_pair_model(time, 0);
  ASSERT_TRUE(a.ste.has_value() && t.ste.has_value());
  ASSERT_EQ(a.ste->size(), 10u);
  ASSERT_EQ(t.ste->size(), a.ste->size());
  for (std::size_t j = 0; j < a.ste->size(); ++j)
    EXPECT_NEAR(t.ste->ste_m()[j], a.ste->ste_m()[j], 1e-15 * a.ste->ste_m()[j]) << "row " << j;
  // The same file at another speed spans 1.5 mesh periods: refused, naming the abscissa.
  EXPECT_THROW(
      (void)build_pair_model(
          load(dir, kMaterial + kSpur + "ste_file = \"time.csv\"\nste_speed_rpm = 1500\n"), 0),
      InputError);
}

// ---------------------------------------------------------------------------------------------
// Bad input

struct ErrorCase {
  const char* name;
  std::string text;       ///< appended to kMaterial (6 lines)
  int line;               ///< absolute line in model.toml (0: not checked)
  std::string key;        ///< InputError::key_path()
  std::string expected;   ///< part of InputError::expected()
  std::string found;      ///< part of InputError::found()
  bool at_check = false;  ///< found by check_inputs, not by the parser
  std::string file = "model.toml";
};

class GearanErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(GearanErrors, NameFileLineKeyExpectedFound) {
  const ErrorCase& c = GetParam();
  const fs::path dir = fresh_dir(std::string("error_") + c.name);
  write_file(dir / "ste_bad.csv", "angle_deg, ste_um\n0, 2\n6, 3\n12, x\n");
  write_file(dir / "measured_hz.csv", "frequency_hz, amplitude_m\n1,1\n2,2\n3,5\n4,2\n5,1\n");
  write_file(dir / "ste_time.csv", "time_ms, ste_um\n0, 2\n1, 3\n2, 2.5\n");
  write_file(dir / "ste_two.csv",
             "angle_deg, ste_um@50Nm, ste_um@80Nm\n0, 2, 3\n6, 3, 4\n12, 2.5, 3.5\n");
  std::optional<InputError> error;
  try {
    const model::Model m = load(dir, kMaterial + c.text);
    EXPECT_TRUE(c.at_check) << "the parser accepted it";
    check_inputs(m, {});
  } catch (const InputError& e) {
    error = e;
  }
  ASSERT_TRUE(error.has_value()) << "no InputError";
  SCOPED_TRACE(error->what());
  EXPECT_EQ(error->key_path(), c.key);
  EXPECT_NE(error->expected().find(c.expected), std::string::npos) << error->expected();
  EXPECT_NE(error->found().find(c.found), std::string::npos) << error->found();
  EXPECT_NE(error->where().file.find(c.file), std::string::npos) << error->where().file;
  if (c.line > 0) {
    EXPECT_EQ(error->where().line, c.line);
  }
}

// kMaterial has 6 lines; kSpur starts at line 7 ([[gear_pairs]]) and ends at line 13.
INSTANTIATE_TEST_SUITE_P(
    AllClasses, GearanErrors,
    ::testing::Values(
        ErrorCase{"HelixOnSpur", kSpur + "helix_angle_deg = 10\n", 14,
                  "gear_pairs[0].helix_angle_deg", "with type = \"spur\"",
                  "the unknown key 'helix_angle_deg'"},
        ErrorCase{"TeethMissing",
                  "[[gear_pairs]]\nname = \"p\"\nteeth1 = 20\nmodule = 0.003\nface_width = "
                  "0.02\ntorque = 100\n",
                  7, "gear_pairs[0].teeth2", "", "without it"},
        ErrorCase{"TorqueNegative",
                  kSpur + "[[gear_pairs]]\nname=\"b\"\nteeth1 = 20\n"
                          "teeth2 = 40\nmodule = 0.003\nface_width = 0.02\ntorque = -5\n",
                  20, "gear_pairs[1].torque", "> 0", "-5"},
        ErrorCase{"InternalWithFewerTeeth",
                  "[[gear_pairs]]\nname = \"p\"\ninternal = true\nteeth1 = 40\nteeth2 = 30\n"
                  "module = 0.003\nface_width = 0.02\ntorque = 100\n",
                  11, "gear_pairs[0].teeth2", "more teeth than gear 1", "30"},
        ErrorCase{"InternalBevel",
                  "[[gear_pairs]]\nname = \"p\"\ntype = \"straight_bevel\"\ninternal = true\n"
                  "teeth1 = 20\nteeth2 = 30\nmodule = 0.003\nface_width = 0.02\ntorque = 100\n",
                  10, "gear_pairs[0].internal", "with type = \"straight_bevel\"",
                  "the unknown key 'internal'"},
        ErrorCase{"DuplicatePairName", kSpur + kSpur, 15, "gear_pairs[1].name",
                  "a name not used by another", "\"spur\""},
        ErrorCase{"UnknownMaterial", kSpur + "material1 = \"steal\"\n", 14,
                  "gear_pairs[0].material1", "a material name", "\"steal\""},
        ErrorCase{"RimWithoutWeb", kSpur + "rim_thickness = 0.01\n", 7,
                  "gear_pairs[0].web_thickness", "rim_thickness and web_thickness together",
                  "only one"},
        ErrorCase{"InterpolationWithoutFile", kSpur + "ste_interpolation = \"hold\"\n", 14,
                  "gear_pairs[0].ste_interpolation", "an ste_file", "no ste_file"},
        ErrorCase{"ShiftOutOfRange", kSpur + "ste_shift = 1.0\n", 14, "gear_pairs[0].ste_shift",
                  "[0, 1)", "1"},
        // Needs the gear library: found by check_inputs, at the pair's table.
        ErrorCase{"ContactRatioBelowOne", kSpur + "addendum_coefficient = 0.5\n", 7,
                  "gear_pairs[0]", "contact ratio eps_alpha >= 1", "eps_alpha = 0.", true},
        ErrorCase{"Interference",
                  "[[gear_pairs]]\nname = \"p\"\nteeth1 = 8\nteeth2 = 60\nmodule = 0.003\n"
                  "face_width = 0.02\ntorque = 100\n",
                  7, "gear_pairs[0].teeth1", "no involute interference", "", true},
        ErrorCase{"SteFileMissing", kSpur + "ste_file = \"nothing.csv\"\n", 7,
                  "gear_pairs[0].ste_file", "a readable STE CSV file", "nothing.csv", true},
        ErrorCase{"SteFileBadCell", kSpur + "ste_file = \"ste_bad.csv\"\n", 4, "ste_um",
                  "a finite number", "x", true, "ste_bad.csv"},
        ErrorCase{"TorqueOutsideSteFile", kSpur + "ste_file = \"ste_two.csv\"\n", 7,
                  "gear_pairs[0].torque", "", "", true},
        ErrorCase{"SteTimeWithoutSpeed", kSpur + "ste_file = \"ste_time.csv\"\n", 1, "time_ms",
                  "mesh period", "none", true, "ste_time.csv"},
        ErrorCase{"SteSpeedWithoutFile", kSpur + "ste_speed_rpm = 1000\n", 14,
                  "gear_pairs[0].ste_speed_rpm", "an ste_file", "no ste_file"},
        // Analyses.
        ErrorCase{"AnalysisWithoutPairs",
                  "[[nodes]]\nname = \"n\"\nposition = [0, 0, 0]\n[[analyses]]\nname = \"a\"\n"
                  "type = \"gear_pair\"\n",
                  12, "analyses[0].type", "gear pair exists", "no [[gear_pairs]]"},
        ErrorCase{"UnknownPair",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"gear_pair\"\npair = \"spru\"\n", 17,
                  "analyses[0].pair", "a gear pair name", "\"spru\""},
        ErrorCase{
            "PairNeededWithTwoPairs",
            kSpur + "[[gear_pairs]]\nname = \"other\"\nteeth1 = 20\nteeth2 = 40\n"
                    "module = 0.003\nface_width = 0.02\ntorque = 100\n[[analyses]]\nname = \"a\"\n"
                    "type = \"mesh_force\"\nspeed_rpm = [1000]\nmodel = \"infinite_inertia\"\n",
            21, "analyses[0].pair", "the name of the gear pair", "nothing"},
        ErrorCase{"DynamicWithoutInertia",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_force\"\nspeed_rpm = [1000]\n",
                  7, "gear_pairs[0].inertia1", "polar inertia of gear 1", "nothing"},
        ErrorCase{"SpeedZero",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_force\"\n"
                          "speed_rpm = [0, 100]\nmodel = \"infinite_inertia\"\n",
                  17, "analyses[0].speed_rpm", "speeds > 0 rpm", "0 rpm"},
        ErrorCase{"TooManyDetails",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_force\"\n"
                          "speed_rpm = [100]\nmodel = \"infinite_inertia\"\n"
                          "detail_rpm = [1, 2, 3, 4, 5, 6, 7, 8, 9]\n",
                  19, "analyses[0].detail_rpm", "at most 8", "9 speeds"},
        ErrorCase{"HarmonicsSpeedMissing",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_harmonics\"\n", 14,
                  "analyses[0].speed_rpm", "", "without it"},
        ErrorCase{"NodalDiameterAboveHalfTeeth",
                  kSpur +
                      "[[analyses]]\nname = \"a\"\ntype = \"mesh_harmonics\"\n"
                      "speed_rpm = 1000\nmodel = \"infinite_inertia\"\nnodal_diameters = [1, 11]\n",
                  19, "analyses[0].nodal_diameters[1]", "0 .. N / 2 = 10", "11"},
        ErrorCase{"GearThree",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_harmonics\"\n"
                          "speed_rpm = 1000\ngear = 3\n",
                  18, "analyses[0].gear", "[1, 2]", "3"},
        ErrorCase{"WindowContactRatioAboveThree",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"mesh_harmonics\"\n"
                          "speed_rpm = 1000\ncontact_ratio = 3.5\n",
                  18, "analyses[0].contact_ratio", "[1, 3]", "3.5"},
        ErrorCase{"MeasuredFileMissing",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"correlation\"\n"
                          "measured_file = \"none.csv\"\n",
                  14, "analyses[0].measured_file", "a readable measured-response CSV", "none.csv",
                  true},
        ErrorCase{"ReferenceRpmForFrequencyFile",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"correlation\"\n"
                          "measured_file = \"measured_hz.csv\"\nreference_peak_rpm = 100\n",
                  14, "analyses[0].reference_peak_rpm", "reference_peak_hz for a measured file",
                  "reference_peak_rpm", true},
        ErrorCase{"ReferenceQWithoutPeak",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"correlation\"\n"
                          "measured_file = \"measured_hz.csv\"\nreference_q = 10\n",
                  18, "analyses[0].reference_q", "reference_peak_rpm or reference_peak_hz",
                  "no reference peak"},
        ErrorCase{"BothReferencePeaks",
                  kSpur + "[[analyses]]\nname = \"a\"\ntype = \"correlation\"\n"
                          "measured_file = \"measured_hz.csv\"\nreference_peak_rpm = 100\n"
                          "reference_peak_hz = 10\n",
                  0, "analyses[0].reference_peak_hz", "", ""}),
    [](const ::testing::TestParamInfo<ErrorCase>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace geardyn::analyses
