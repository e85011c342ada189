// The loaded tooth contact analysis (type = "tooth_contact") of bevel and hypoid pairs from model
// files (docs/theory.md §15.9): the [gear_pairs.ease_off] table and the mounting-error keys of
// [gear_pairs.contact] reach the contact model in SI units, the loaded flank follows hand and
// rotation as for the tooth forces, the analysis runs and states its approximation, and the
// keys are refused on cylindrical pairs at their own key paths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/gear/tooth_forces.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;

const std::string kBevel = R"(version = 1
[[gear_pairs]]
name = "bevel"
type = "spiral_bevel"
teeth1 = 36
teeth2 = 48
module = 0.004
helix_angle_deg = 30
hand = "right"
rotation = "cw"
face_width = 0.03
shaft_angle_deg = 90
torque = 200

[gear_pairs.ease_off]
profile_crowning = 12e-6
length_crowning = 20e-6
bias = 5e-6
profile_slope = 1e-6
length_slope = -2e-6

[gear_pairs.contact]
positions = 24
slices = 20
mounting_h = 0.1e-3
mounting_v = -0.05e-3
mounting_j = 0.02e-3
shaft_angle_error_deg = 0.05

[[analyses]]
name = "ltca"
type = "tooth_contact"
)";

TEST(BevelToothContactAnalysis, KeysReachTheModelAndTheAnalysisRuns) {
  const model::Model m = load(fresh_dir("bevel_ltca"), kBevel);
  const auto tc = build_tooth_contact_model(m, 0);
  const gear::EaseOff& e = tc->options.ease_off;
  EXPECT_EQ(e.profile_crowning_m, 12e-6);
  EXPECT_EQ(e.length_crowning_m, 20e-6);
  EXPECT_EQ(e.bias_m, 5e-6);
  EXPECT_EQ(e.profile_slope_m, 1e-6);
  EXPECT_EQ(e.length_slope_m, -2e-6);
  const gear::MountingErrors& h = tc->options.mounting;
  EXPECT_EQ(h.h_m, 0.1e-3);
  EXPECT_EQ(h.v_m, -0.05e-3);
  EXPECT_EQ(h.j_m, 0.02e-3);
  EXPECT_NEAR(h.shaft_angle_rad, 0.05 * std::numbers::pi / 180.0, 1e-18);
  // Right hand, clockwise, driving: the rule of gear/tooth_forces.hpp.
  EXPECT_EQ(h.pinion_concave_loaded,
            gear::loaded_flank(gear::SpiralHand::Right, gear::Rotation::Clockwise,
                               gear::MemberRole::Driving) == gear::Flank::Concave);
  EXPECT_TRUE(tc->contact->bevel());
  // The contact runs on the virtual pair with the centre distance changed by the mounting
  // errors, Delta a = H sin(delta1) + J sin(delta2) + Delta Sigma R_m (15.22).
  const gear::GearPairGeometry& g = tc->pair.geometry;
  const double da = h.h_m * std::sin(g.pinion.pitch_cone_angle_rad) +
                    h.j_m * std::sin(g.wheel.pitch_cone_angle_rad) +
                    h.shaft_angle_rad * g.mean_cone_distance_m;
  EXPECT_NEAR(tc->contact->geometry().centre_distance_m, g.centre_distance_m + da, 1e-15);
  const Outcome o = type_of(m.analyses[0]).run(m, m.analyses[0], Context(m, m.analyses[0]));
  EXPECT_EQ(o.output.status, Status::Ok) << o.output.message;
  bool noted = false;
  for (const auto& n : o.output.notes) noted |= n.find("virtual cylindrical pair") != n.npos;
  EXPECT_TRUE(noted);
}

TEST(BevelToothContactAnalysis, EaseOffAndMountingErrorsAreRefusedOnCylindricalPairs) {
  const std::string spur = R"(version = 1
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
)";
  const std::string analysis = "[[analyses]]\nname = \"ltca\"\ntype = \"tooth_contact\"\n";
  auto fails = [&](const std::string& extra, const std::string& key) {
    try {
      const model::Model m = load(fresh_dir("bevel_ltca_bad"), spur + extra + analysis);
      check_inputs(m, {});
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
    }
  };
  fails("[gear_pairs.ease_off]\nprofile_crowning = 5e-6\n", "gear_pairs[0].ease_off");
  fails("[gear_pairs.contact]\nmounting_h = 1e-4\n", "gear_pairs[0].contact.mounting_h");
}

}  // namespace
}  // namespace geardyn::analyses
