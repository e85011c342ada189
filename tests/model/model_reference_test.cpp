// The declaration table documents itself: analyses::schema_markdown() lists every key, the
// checked-in docs/model-reference.md and fuzz/model.dict are what the table generates, and key
// names follow the unit convention (only *_rpm, *_hz, *_deg keys take non-SI units).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema.hpp"

namespace geardyn::model {
namespace {

const std::string kReference = std::string(GEARDYN_SOURCE_DIR) + "/docs/model-reference.md";
const std::string kDictionary = std::string(GEARDYN_SOURCE_DIR) + "/fuzz/model.dict";
constexpr const char* kRegenerate =
    "regenerate with: GEARDYN_UPDATE_DOCS=1 <build>/tests/model/test_model "
    "--gtest_filter='ModelReference.*'";

void for_each_field(const Section& s, const std::function<void(const Section&, const Field&)>& f) {
  for (const auto& field : s.fields) f(s, field);
  for (const auto& sub : s.sections) for_each_field(sub, f);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool update_requested() {
  const char* v = std::getenv("GEARDYN_UPDATE_DOCS");
  return v && std::string(v) == "1";
}

/// libFuzzer dictionary: every key, section header and choice of the schema.
std::string fuzz_dictionary() {
  std::set<std::string> tokens;
  std::function<void(const Section&, const std::string&)> walk = [&](const Section& s,
                                                                     const std::string& prefix) {
    for (const auto& f : s.fields) {
      tokens.insert(fmt::format("\"{} = \"", f.name));
      for (const auto& c : f.choices) tokens.insert(fmt::format("\"\\\"{}\\\"\"", c));
    }
    for (const auto& v : s.variants) tokens.insert(fmt::format("\"\\\"{}\\\"\"", v.name));
    for (const auto& sub : s.sections) {
      const std::string name = prefix.empty() ? sub.name : prefix + "." + sub.name;
      tokens.insert(sub.kind == SectionKind::Table ? fmt::format("\"[{}]\"", name)
                                                   : fmt::format("\"[[{}]]\"", name));
      walk(sub, name);
    }
  };
  walk(analyses::model_schema(), "");
  std::string out =
      "# libFuzzer dictionary for fuzz/model_fuzz, generated from the model schema by\n"
      "# tests/model/model_reference_test.cpp (GEARDYN_UPDATE_DOCS=1 test_model).\n";
  for (const char* t :
       {"\"\\x0a\"", "\"=\"", "\"[\"", "\"]\"", "\"{\"", "\"}\"", "\",\"", "\"\\\"\"", "\"true\"",
        "\"false\"", "\"inf\"", "\"nan\"", "\"1e9\"", "\"-1\"", "\"0.5\"", "\".0\"", "\"all\""})
    out += std::string(t) + "\n";
  for (const auto& t : tokens) out += t + "\n";
  return out;
}

void check_generated(const std::string& path, const std::string& generated) {
  if (update_requested()) {
    std::ofstream(path, std::ios::binary) << generated;
    GTEST_SKIP() << "wrote " << path;
  }
  const std::string on_disk = read_file(path);
  if (on_disk != generated) {
    std::size_t at = 0;
    while (at < on_disk.size() && at < generated.size() && on_disk[at] == generated[at]) ++at;
    const auto line =
        std::count(generated.begin(), generated.begin() + static_cast<long>(at), '\n');
    FAIL() << path << " is out of date with the schema (first difference on line " << line + 1
           << "); " << kRegenerate;
  }
}

TEST(ModelReference, MarkdownListsEveryKey) {
  const std::string md = analyses::schema_markdown();
  int keys = 0;
  for_each_field(analyses::model_schema(), [&](const Section& s, const Field& f) {
    ++keys;
    EXPECT_NE(md.find(fmt::format("| `{}` |", f.name)), std::string::npos)
        << s.title << " " << f.name;
    EXPECT_FALSE(f.help.empty()) << f.name;
  });
  EXPECT_GT(keys, 150);
  std::function<void(const Section&)> sections = [&](const Section& s) {
    for (const auto& sub : s.sections) {
      EXPECT_NE(md.find("# " + sub.title), std::string::npos) << sub.title;
      sections(sub);
    }
    for (const auto& v : s.variants)
      EXPECT_NE(md.find(fmt::format("# {} = \"{}\"", s.discriminator, v.name)), std::string::npos);
  };
  sections(analyses::model_schema());
  // A few entries in full: type, unit, default, range and help of one key.
  EXPECT_NE(md.find("| `length` | number | m | **required** | > 0 | Length of the section. |"),
            std::string::npos);
  EXPECT_NE(md.find("| `speed_count` | integer |  | `51` | in [2, 100000] |"), std::string::npos);
}

TEST(ModelReference, DocsFileIsUpToDate) {
  check_generated(kReference, analyses::schema_markdown());
}

TEST(ModelReference, FuzzDictionaryIsUpToDate) { check_generated(kDictionary, fuzz_dictionary()); }

TEST(ModelReference, OnlyKeysNamedForAUnitUseIt) {
  for_each_field(analyses::model_schema(), [](const Section& s, const Field& f) {
    const std::string unit = f.unit.symbol;
    auto ends_with = [&](const char* suffix) {
      const std::string sfx(suffix);
      return f.name.size() > sfx.size() &&
             f.name.compare(f.name.size() - sfx.size(), sfx.size(), sfx) == 0;
    };
    EXPECT_EQ(ends_with("_rpm"), unit == "rpm") << s.title << " " << f.name;
    EXPECT_EQ(ends_with("_hz"), unit == "Hz") << s.title << " " << f.name;
    EXPECT_EQ(ends_with("_deg"), unit == "deg") << s.title << " " << f.name;
    const bool converted = unit == "rpm" || unit == "Hz" || unit == "deg";
    EXPECT_EQ(f.unit.to_si != 1.0, converted) << s.title << " " << f.name;
  });
}

TEST(ModelReference, ClosestMatch) {
  const std::vector<std::string> keys = {"length", "outer_diameter", "inner_diameter", "phase_deg",
                                         "speed_rpm"};
  EXPECT_EQ(closest_match("lenght", keys), "length");                 // swap
  EXPECT_EQ(closest_match("outer_diamter", keys), "outer_diameter");  // missing letter
  EXPECT_EQ(closest_match("Length", keys), "length");                 // case
  EXPECT_EQ(closest_match("phase", keys), "phase_deg");               // unit suffix left out
  EXPECT_EQ(closest_match("speed", keys), "speed_rpm");
  EXPECT_EQ(closest_match("colour", keys), "");  // nothing close
  EXPECT_EQ(closest_match("", keys), "");
}

}  // namespace
}  // namespace geardyn::model
