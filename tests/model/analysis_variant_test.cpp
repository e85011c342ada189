// Per-analysis model variants (`set = [...]`) and linked sweep parameters: checked like --set
// before any computation, with the analysis's key path in the message.
#include <gtest/gtest.h>

#include <optional>

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

const std::string kFullModel =
    std::string(GEARDYN_SOURCE_DIR) + "/tests/model/data/full_model.toml";

std::optional<InputError> build_error(ModelDocument doc) {
  try {
    (void)build_model(doc);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

TEST(AnalysisVariant, SetEntriesAreReadAndValidated) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "analyses[0].set=[\"gear_meshes[0].stiffness=0\", \"bearings[0].kxx=5e6\"]");
  const Model m = build_model(doc);
  ASSERT_EQ(m.analyses[0].overrides.size(), 2u);
  EXPECT_EQ(m.analyses[0].overrides[0], "gear_meshes[0].stiffness=0");
  // The base model is unchanged: the variant applies to this analysis only.
  EXPECT_EQ(m.gear_meshes[0].stiffness,
            build_model(analyses::load_document(kFullModel)).gear_meshes[0].stiffness);
}

TEST(AnalysisVariant, UnknownKeyInSetIsAnInputErrorAtTheAnalysis) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "analyses[0].set=[\"gear_meshes[0].stifness=0\"]");
  const auto e = build_error(doc);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->key_path(), "analyses[0].set[0]");
  EXPECT_NE(std::string(e->what()).find("stiffness"), std::string::npos) << e->what();
}

TEST(AnalysisVariant, OutOfRangeValueInSetIsAnInputError) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "analyses[0].set=[\"bearings[0].kxx=-1\"]");
  const auto e = build_error(doc);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->key_path(), "analyses[0].set");
  EXPECT_NE(std::string(e->what()).find("bearings[0].kxx"), std::string::npos) << e->what();
}

TEST(SweepLinkedParameters, ReadAndChecked) {
  ModelDocument doc = analyses::load_document(kFullModel);
  apply_override(doc, "analyses[6].linked_parameters=[\"bearings[0].kyy\"]");
  const Model m = build_model(doc);
  const auto& s = m.analyses[6].settings_of<analyses::SweepSettings>();
  ASSERT_EQ(s.linked_parameters.size(), 1u);
  EXPECT_EQ(s.linked_parameters[0], "bearings[0].kyy");

  ModelDocument bad = analyses::load_document(kFullModel);
  apply_override(bad, "analyses[6].linked_parameters=[\"bearings[0].name\"]");
  const auto e = build_error(bad);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->key_path(), "bearings[0].name");
  EXPECT_NE(std::string(e->what()).find("number"), std::string::npos) << e->what();
}

}  // namespace
}  // namespace geardyn::model
