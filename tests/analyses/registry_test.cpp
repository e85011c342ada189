// The registry is the one list of analysis types: the schema's `type` choices and variants,
// the sweep's output quantities, dispatch and the reference all come from it and must agree.
#include "geardyn/analyses/registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "geardyn/analyses/model_file.hpp"

namespace geardyn::analyses {
namespace {

const model::Section& analyses_section() {
  const model::Section* s = model_schema().find_section("analyses", "");
  EXPECT_NE(s, nullptr);
  return *s;
}

TEST(Registry, NamesAreUniqueAndEachTypeIsComplete) {
  std::set<std::string> names;
  for (const auto& t : registry()) {
    EXPECT_TRUE(names.insert(t.name).second) << t.name << " registered twice";
    ASSERT_TRUE(t.declare) << t.name;
    ASSERT_TRUE(t.run) << t.name;
    const model::AnalysisDeclaration d = t.declare();
    EXPECT_EQ(d.name, t.name) << "a type declares the keys of another";
    ASSERT_TRUE(d.make_settings) << t.name;
    EXPECT_NE(d.make_settings(), nullptr) << t.name;
    EXPECT_FALSE(d.help.empty()) << t.name;
    EXPECT_EQ(t.scalars.empty(), !t.scalar) << t.name << ": scalars and their reader go together";
    EXPECT_EQ(find_analysis_type(t.name), &t);
  }
  EXPECT_EQ(find_analysis_type("no_such_type"), nullptr);
}

TEST(Registry, SchemaTypeChoicesAndVariantsAreTheRegistry) {
  const model::Section& s = analyses_section();
  const model::Field* type = s.find_field("type", "");
  ASSERT_NE(type, nullptr);
  ASSERT_EQ(type->choices.size(), registry().size());
  ASSERT_EQ(s.variants.size(), registry().size());
  for (std::size_t i = 0; i < registry().size(); ++i) {
    EXPECT_EQ(type->choices[i], registry()[i].name);
    EXPECT_EQ(s.variants[i].name, registry()[i].name);
  }
  // Every key restricted to a type names a registered type.
  for (const auto& f : s.fields)
    for (const auto& v : f.only_in) EXPECT_NE(find_analysis_type(v), nullptr) << f.name;
}

TEST(Registry, TheParserMakesEachTypesSettings) {
  for (const auto& t : registry()) {
    model::Analysis a;
    a.name = "a";
    a.type = t.name;
    a.settings = t.declare().make_settings();
    EXPECT_EQ(&type_of(a), &t);
    // The settings survive a copy of the analysis (a sweep and a `set` variant copy models).
    const model::Analysis copy = a;
    EXPECT_NE(copy.settings.get(), nullptr);
    EXPECT_NE(copy.settings.get(), a.settings.get());
  }
}

TEST(Registry, EveryAnalysisOffersScalarsToSweepsAndDesignStudies) {
  // Issue [architecture]: every analysis is sweepable. A sweep cannot target a sweep; every
  // other type declares at least one scalar, each with a meaning and only parameters that
  // [[analyses.outputs]] has; a name offered by several types has one unit everywhere.
  const std::set<std::string> parameters = {"mode", "sensor", "channel", "at_rpm", "at_hz"};
  std::map<std::string, std::string> unit_of;
  for (const auto& t : registry()) {
    if (t.name == "sweep") {
      EXPECT_TRUE(t.scalars.empty());
      continue;
    }
    EXPECT_FALSE(t.scalars.empty()) << t.name << " offers no scalar";
    std::set<std::string> names;
    for (const auto& s : t.scalars) {
      EXPECT_TRUE(names.insert(s.name).second) << t.name << ": " << s.name << " twice";
      EXPECT_FALSE(s.meaning.empty()) << t.name << "." << s.name;
      for (const auto& p : s.parameters) {
        EXPECT_TRUE(parameters.count(p)) << t.name << "." << s.name << " reads " << p;
      }
      const auto [it, inserted] = unit_of.emplace(s.name, s.unit);
      // A response amplitude is in m or rad (set per sensor); a peak location in Hz or rpm.
      const bool unit_varies =
          s.name == "peak_amplitude" || s.name == "peak_location" || s.name == "amplitude_at";
      if (!inserted && !unit_varies) {
        EXPECT_EQ(it->second, s.unit) << s.name << " has two units";
      }
    }
  }
}

TEST(Registry, SweepOutputsAreTheScalarsTheTypesOffer) {
  std::vector<std::string> offered;
  for (const auto& t : registry())
    for (const auto& sc : t.scalars)
      if (std::find(offered.begin(), offered.end(), sc.name) == offered.end())
        offered.push_back(sc.name);
  const model::Section* outputs = analyses_section().find_section("outputs", "sweep");
  ASSERT_NE(outputs, nullptr);
  const model::Field* quantity = outputs->find_field("quantity", "");
  ASSERT_NE(quantity, nullptr);
  EXPECT_EQ(quantity->choices, offered);
}

TEST(Registry, TheReferenceDocumentsEveryType) {
  const std::string md = schema_markdown();
  for (const auto& t : registry())
    EXPECT_NE(md.find("type = \"" + t.name + "\""), std::string::npos) << t.name;
}

TEST(Registry, AnUnregisteredTypeIsALogicError) {
  model::Analysis a;
  a.name = "x";
  a.type = "not_registered";
  EXPECT_THROW((void)type_of(a), std::logic_error);
}

}  // namespace
}  // namespace geardyn::analyses
