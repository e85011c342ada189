// The corpus of bad and odd inputs (tests/corpus/README.md): every file through `check` and
// `run`, asserting its header's exit code and messages, that no input ends in a signal, that
// check and run agree, and what is left on disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace {

using namespace geardyn::cli_test;

struct CorpusEntry {
  fs::path file;
  std::string description;
  int run_exit = -1;
  std::vector<std::string> expects;
  std::vector<std::string> values;  // "<file> <column> <row> <value> <relative tolerance>"
  std::string args;
};

CorpusEntry read_entry(const fs::path& file) {
  CorpusEntry e;
  e.file = file;
  std::ifstream in(file, std::ios::binary);
  std::string line;
  auto value = [&](const std::string& key) -> std::string {
    const std::size_t at = line.find(key);
    return at == std::string::npos ? std::string() : line.substr(at + key.size());
  };
  while (std::getline(in, line)) {
    if (line.rfind("\xef\xbb\xbf", 0) == 0) line.erase(0, 3);
    if (line.rfind("#", 0) != 0) break;  // the header is the leading comment block
    if (line.find("# corpus: ") == 0) e.description = value("# corpus: ");
    if (line.find("# run-exit: ") == 0) e.run_exit = std::stoi(value("# run-exit: "));
    if (line.find("# expect: ") == 0) e.expects.push_back(value("# expect: "));
    if (line.find("# args: ") == 0) e.args = value("# args: ");
    if (line.find("# expect-value: ") == 0) e.values.push_back(value("# expect-value: "));
  }
  return e;
}

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kSource + "/tests/corpus"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

class Corpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(Corpus, HandledAsItsHeaderSays) {
  const CorpusEntry e = read_entry(GetParam());
  ASSERT_FALSE(e.description.empty()) << e.file << ": no '# corpus:' line";
  ASSERT_TRUE(e.run_exit == 0 || e.run_exit == 1 || e.run_exit == 2) << e.file;
  const fs::path out = fresh_dir("corpus_" + e.file.stem().string());

  const ProcessResult check = run("check " + e.file.string());
  const ProcessResult r = run("run -q " + e.file.string() + " -o " + out.string() + " " + e.args);
  // A signal shows as -1 (not WIFEXITED) or as 128 + its number (through the shell).
  auto signalled = [](int code) { return code < 0 || code >= 128; };
  ASSERT_FALSE(signalled(check.exit_code)) << "check ended on a signal: " << check.err;
  ASSERT_FALSE(signalled(r.exit_code)) << "run ended on a signal: " << r.err;
  EXPECT_EQ(r.exit_code, e.run_exit) << e.description << "\n" << r.err;
  for (const auto& text : e.expects)
    EXPECT_NE(r.err.find(text), std::string::npos) << "run stderr lacks '" << text << "':\n"
                                                   << r.err;

  // check refuses exactly what run refuses as bad input, with the same message.
  EXPECT_EQ(check.exit_code, r.exit_code == 2 ? 2 : 0) << check.err;
  if (r.exit_code == 2) {
    EXPECT_EQ(first_line(check.err), first_line(r.err));
    EXPECT_FALSE(fs::exists(out)) << "bad input left a results folder";
  } else {
    ASSERT_TRUE(fs::exists(out / "manifest.json")) << r.err;
    const auto m = read_json(out / "manifest.json");
    EXPECT_EQ(m["complete"], true);
    EXPECT_EQ(m["status"] == "ok", r.exit_code == 0) << m["status"];
    // Numbers the header states, read back from the CSV the run wrote.
    for (const auto& spec : e.values) {
      std::istringstream in(spec);
      std::string file, column;
      std::size_t row = 0;
      double expected = 0.0, tolerance = 0.0;
      ASSERT_TRUE(in >> file >> column >> row >> expected >> tolerance) << spec;
      const auto table = read_csv(out / file);
      ASSERT_TRUE(table.count(column)) << spec;
      ASSERT_LT(row, table.at(column).size()) << spec;
      EXPECT_NEAR(std::stod(table.at(column)[row]), expected, tolerance * std::abs(expected))
          << spec;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Inputs, Corpus, ::testing::ValuesIn(corpus_files()),
                         [](const ::testing::TestParamInfo<fs::path>& param) {
                           std::string name = param.param.stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
