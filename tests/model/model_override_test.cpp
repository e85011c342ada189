// `--set key.path=value` overrides and sweep values (set_number): checked against the schema,
// converted like values in the file, reported with the assignment as their location, and
// applied to a cheap copy of the document without touching the original.
#include <gtest/gtest.h>

#include <numbers>
#include <optional>
#include <thread>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::model {

using namespace ::geardyn::analyses;  // NOLINT: the settings types of every analysis
namespace {

constexpr double kPi = std::numbers::pi;
const std::string kFullModel =
    std::string(GEARDYN_SOURCE_DIR) + "/tests/model/data/full_model.toml";

template <class F>
std::optional<InputError> error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

TEST(ModelOverride, SetsValuesWithTheirUnits) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "bearings[0].kxx=2e7");
  apply_override(doc, "analyses[0].speed_rpm=6000");  // modal: rpm -> rad/s
  apply_override(doc, "gear_meshes[0].stiffness=1e8");
  apply_override(doc, "gear_meshes[0].helix_angle_deg = 30");  // spaces around '=' are fine
  apply_override(doc, "shafts[0].theory=euler_bernoulli");     // quotes optional for strings
  apply_override(doc, "shafts[0].elements[1].divisions=3");
  apply_override(doc, "damping.bands[1].ratio=0.2");
  apply_override(doc, "analyses[1].engine_orders=[1, 2, 3]");
  const Model m = build_model(doc);
  EXPECT_EQ(m.bearings[0].stiffness[0][0], 2e7);
  EXPECT_DOUBLE_EQ(m.analyses[0].settings_of<analyses::ModalSettings>().speed, 6000 * 2 * kPi / 60);
  EXPECT_EQ(m.gear_meshes[0].stiffness, 1e8);
  EXPECT_DOUBLE_EQ(m.gear_meshes[0].helix_angle, kPi / 6);
  EXPECT_EQ(m.shafts[0].theory, BeamTheory::EulerBernoulli);
  EXPECT_EQ(m.shafts[0].elements[1].divisions, 3);
  EXPECT_EQ(m.damping.bands[1].ratio, 0.2);
  EXPECT_EQ(m.analyses[1].settings_of<analyses::CampbellSettings>().engine_orders,
            (std::vector<double>{1, 2, 3}));
}

TEST(ModelOverride, AddsKeysAndTablesThatAreNotInTheFile) {
  ModelDocument doc = analyses::parse_document(R"(version = 1
[[nodes]]
name = "a"
position = [0, 0, 0]
[[bearings]]
node = "a"
kxx = 1e6
)",
                                               "small.toml");
  apply_override(doc, "bearings[0].cyy=50");
  apply_override(doc, "damping.rayleigh_beta=1e-5");  // no [damping] table in the file
  const Model m = build_model(doc);
  EXPECT_EQ(m.bearings[0].damping[0][7], 50.0);
  EXPECT_EQ(m.damping.rayleigh_beta, 1e-5);
}

TEST(ModelOverride, LaterOverrideOfTheSameKeyWins) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "bearings[0].kxx=2e7");
  apply_override(doc, "bearings[0].kxx=3e7");
  EXPECT_EQ(doc.overrides().size(), 1u);
  EXPECT_EQ(build_model(doc).bearings[0].stiffness[0][0], 3e7);
}

TEST(ModelOverride, CopiesAreIndependent) {
  const ModelDocument base = analyses::load_document(kFullModel);
  ModelDocument copy = base;
  set_number(copy, "bearings[0].kxx", 5e7);
  EXPECT_EQ(build_model(copy).bearings[0].stiffness[0][0], 5e7);
  EXPECT_EQ(build_model(base).bearings[0].stiffness[0][0], 1e8);
  EXPECT_TRUE(base.overrides().empty());
  EXPECT_EQ(&copy.table(), &base.table());  // the parsed file is shared, not copied
}

TEST(ModelOverride, SweepPointsOnThreadsMatchSerialResults) {
  // What a threaded sweep does: copy the document per point, set the value, build.
  const ModelDocument base = analyses::load_document(kFullModel);
  const std::vector<double> values = {1e6, 2e6, 4e6, 8e6, 1.6e7, 3.2e7};
  std::vector<double> got(values.size(), 0.0);
  std::vector<std::thread> workers;
  for (std::size_t i = 0; i < values.size(); ++i) {
    workers.emplace_back([&, i] {
      ModelDocument point = base;
      set_number(point, "bearings[1].kyy", values[i]);
      got[i] = build_model(point).bearings[1].stiffness[2][7];
    });
  }
  for (auto& w : workers) w.join();
  EXPECT_EQ(got, values);
}

TEST(ModelOverride, SetNumberUsesTheUnitOfTheKey) {
  ModelDocument doc = analyses::load_document(kFullModel);
  set_number(doc, "analyses[0].speed_rpm", 60.0);
  set_number(doc, "unbalances[0].phase_deg", 90.0);
  set_number(doc, "analyses[0].n_modes", 4.0);  // integer key, integral value
  const Model m = build_model(doc);
  EXPECT_DOUBLE_EQ(m.analyses[0].settings_of<analyses::ModalSettings>().speed, 2 * kPi);
  EXPECT_DOUBLE_EQ(m.unbalances[0].phase, kPi / 2);
  EXPECT_EQ(m.analyses[0].settings_of<analyses::ModalSettings>().n_modes, 4);
}

TEST(ModelOverride, UnknownKeyGetsDidYouMean) {
  ModelDocument doc = analyses::load_document(kFullModel);
  auto e = error_of([&] { apply_override(doc, "bearings[0].kxy2=1"); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().file, "--set bearings[0].kxy2=1");
  EXPECT_EQ(e->key_path(), "bearings[0].kxy2");
  EXPECT_EQ(e->expected(), "a key of [[bearings]]");
  EXPECT_EQ(e->found(), "the unknown key 'kxy2'");
  EXPECT_EQ(e->hint(), "did you mean 'kxy'?");

  e = error_of([&] { apply_override(doc, "bearing[0].kxx=1"); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->key_path(), "bearing[0]");
  EXPECT_EQ(e->hint(), "did you mean 'bearings'?");

  e = error_of([&] { set_number(doc, "gear_meshes[0].stifness", 1e8); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->hint(), "did you mean 'stiffness'?");
  EXPECT_NE(e->where().file.find("sweep value gear_meshes[0].stifness"), std::string::npos);
}

TEST(ModelOverride, PathErrors) {
  ModelDocument doc = analyses::load_document(kFullModel);
  struct Case {
    const char* assignment;
    const char* key;
    const char* expected;
    const char* found;
  };
  const Case cases[] = {
      {"bearings[5].kxx=1", "bearings[5]",
       "an index from 0 to 2 (the model has 3 [[bearings]] "
       "tables)",
       "index 5"},
      {"bearings.kxx=1", "bearings", "an index: bearings[0], bearings[1], ...",
       "'bearings' without an index"},
      {"damping[0].loss_factor=1", "damping[0]", "'damping' without an index", "'damping[0]'"},
      {"point_masses[0].mass.value=1", "point_masses[0].mass", "a table name before the '.'",
       "'mass', which is a key, not a table"},
      {"shafts[0].elements=1", "shafts[0].elements", "a key with a value",
       "'elements', which is a table"},
      {"analyses[1].speed_rpm[0]=1", "analyses[1].speed_rpm[0]", "a key path that ends with a key",
       "'speed_rpm[0]'"},
      {"analyses[0].speed_count=3", "analyses[0].speed_count",
       "a key of [[analyses]] with type = \"modal\"", "the unknown key 'speed_count'"},
      {"bearings[0].kxx", "bearings[0].kxx", "key.path=value", "without '='"},
      {"bearings[0]..kxx=1", "bearings[0]..kxx", "a key path like", "'bearings[0]..kxx'"},
      {"bearings[0].kxx=", "bearings[0].kxx", "a number", "no value after '='"},
      {"bearings[0].kxx=abc", "bearings[0].kxx", "a TOML value: a number >= 0", "'abc'"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.assignment);
    auto e = error_of([&] { apply_override(doc, c.assignment); });
    ASSERT_TRUE(e);
    EXPECT_EQ(e->where().file, std::string("--set ") + c.assignment);
    EXPECT_EQ(e->where().line, 0);
    EXPECT_EQ(e->key_path(), c.key);
    EXPECT_NE(e->expected().find(c.expected), std::string::npos) << e->expected();
    EXPECT_NE(e->found().find(c.found), std::string::npos) << e->found();
    EXPECT_NE(std::string(e->what()).find(std::string("--set ") + c.assignment), std::string::npos);
  }
  EXPECT_TRUE(doc.overrides().empty());  // nothing half-applied
}

TEST(ModelOverride, BadValuesAreReportedAtTheAssignment) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "materials[0].density=-5");
  auto e = error_of([&] { (void)build_model(doc); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().file, "--set materials[0].density=-5");
  EXPECT_EQ(e->key_path(), "materials[0].density");
  EXPECT_NE(e->expected().find(">= 0"), std::string::npos);  // 0: a massless shaft
  EXPECT_EQ(e->found(), "-5");

  ModelDocument doc2 = analyses::load_document(kFullModel);
  apply_override(doc2, "shafts[0].theory=timoshenco");
  e = error_of([&] { (void)build_model(doc2); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->hint(), "did you mean 'timoshenko'?");

  ModelDocument doc3 = analyses::load_document(kFullModel);
  set_number(doc3, "shafts[0].elements[0].outer_diameter", 0.0);
  e = error_of([&] { (void)build_model(doc3); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().file, "sweep value shafts[0].elements[0].outer_diameter = 0");
  EXPECT_EQ(e->found(), "0");
}

TEST(ModelOverride, SetNumberChecksTheKeyType) {
  ModelDocument doc = analyses::load_document(kFullModel);
  auto e = error_of([&] { set_number(doc, "shafts[0].material", 1.0); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->expected(), "the path of a number or integer key");
  e = error_of([&] { set_number(doc, "shafts[0].elements[0].divisions", 2.5); });
  ASSERT_TRUE(e);
  EXPECT_NE(e->expected().find("an integer"), std::string::npos);
  EXPECT_EQ(e->found(), "2.5");
  e = error_of([&] { set_number(doc, "bearings[0].kxx", std::nan("")); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->found(), "nan");
}

TEST(ModelOverride, ChangingTheTypeChangesTheAllowedKeys) {
  ModelDocument doc = analyses::load_document(kFullModel);
  // analyses[0] is modal: speed_count is not one of its keys ...
  EXPECT_TRUE(error_of([&] { apply_override(doc, "analyses[0].speed_count=3"); }));
  // ... until its type is set to campbell; the modal keys in the file are then errors.
  apply_override(doc, "analyses[0].type=campbell");
  apply_override(doc, "analyses[0].speed_count=3");
  auto e = error_of([&] { (void)build_model(doc); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->key_path(), "analyses[0].speed_rpm");  // a number, campbell wants an array
}

}  // namespace
}  // namespace geardyn::model
