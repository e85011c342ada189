#include "geardyn/io/results_writer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geardyn/core/version.hpp"
#include "geardyn/io/sha256.hpp"

namespace geardyn::io {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

AnalysisOutput modal_output() {
  AnalysisOutput out;
  out.name = "modal";
  out.type = "modal";
  out.run_time_s = 0.25;
  out.notes = {"residual of every mode below 1e-9"};
  Table t;
  t.name = "modes";
  t.title = "Natural frequencies";
  t.add("mode", "", {1, 2});
  t.add("frequency_hz", "Hz", {12.5, 40.0});
  t.add_text("whirl", {"forward", "backward"});
  out.tables.push_back(t);
  Table s;
  s.name = "shapes";
  s.add("x_m", "m", {0.0, 0.5, 1.0});
  out.tables.push_back(s);
  return out;
}

AnalysisOutput failed_output() {
  AnalysisOutput out;
  out.name = "unbalance";
  out.type = "harmonic";
  out.status = Status::Singular;
  out.message = "dynamic stiffness singular at 1500 rpm; add bearing damping";
  out.run_time_s = 0.5;
  return out;
}

// Every entry of `dir`'s parent whose name starts with `dir`'s name followed by ".": staging
// folders (".tmp-<pid>") or swapped-out old results (".old-<pid>") left behind.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  const std::string prefix = dir.filename().string() + ".";
  for (const auto& entry : fs::directory_iterator(dir.parent_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0)
      found.push_back(entry.path().filename().string());
  return found;
}

// Hidden entries inside a results folder: analyses or files caught mid-write.
std::vector<std::string> hidden_entries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().front() == '.')
      found.push_back(entry.path().filename().string());
  return found;
}

class ResultsWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    base_ = fs::path(GEARDYN_BINARY_DIR) / "test-output" / "io" / info->name();
    fs::remove_all(base_);
    fs::create_directories(base_);
    outdir_ = base_ / "results";
    model_ = base_ / "model.toml";
    std::ofstream(model_) << "title = \"test rotor\"\n";
    info_.model_path = model_;
    info_.command_line = "geardyn run model.toml -o results";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(base_);
  }

  fs::path base_, outdir_, model_;
  RunInfo info_;
};

TEST_F(ResultsWriterTest, WritesTablesAndManifest) {
  write_results(outdir_, info_, {modal_output(), failed_output()}, "<html>report</html>");

  EXPECT_EQ(read_text(outdir_ / "modal" / "modes.csv"),
            "mode,frequency_hz,whirl\n1,12.5,forward\n2,40,backward\n");
  EXPECT_EQ(read_text(outdir_ / "modal" / "shapes.csv"), "x_m\n0\n0.5\n1\n");
  EXPECT_EQ(read_text(outdir_ / "report.html"), "<html>report</html>");
  EXPECT_TRUE(fs::is_directory(outdir_ / "unbalance"));
  EXPECT_TRUE(leftovers(outdir_).empty());
  EXPECT_TRUE(hidden_entries(outdir_).empty());

  const nlohmann::json m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["manifest_version"], kManifestVersion);
  EXPECT_EQ(m["geardyn_version"], kVersion);
  EXPECT_EQ(m["status"], "failed");  // one analysis failed
  EXPECT_EQ(m["complete"], true);
  EXPECT_TRUE(m["not_run"].empty());
  EXPECT_TRUE(m["kept_files"].empty());
  EXPECT_EQ(m["model"]["path"], model_.string());
  EXPECT_EQ(m["model"]["sha256"], sha256_file(model_));
  EXPECT_EQ(m["command_line"], info_.command_line);
  EXPECT_EQ(m["report"], "report.html");
  const std::regex iso8601(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z)");
  EXPECT_TRUE(std::regex_match(m["start_time"].get<std::string>(), iso8601)) << m["start_time"];
  EXPECT_TRUE(std::regex_match(m["finish_time"].get<std::string>(), iso8601));

  ASSERT_EQ(m["analyses"].size(), 2u);
  const auto& modal = m["analyses"][0];
  EXPECT_EQ(modal["name"], "modal");
  EXPECT_EQ(modal["type"], "modal");
  EXPECT_EQ(modal["status"], "ok");
  EXPECT_EQ(modal["message"], "");
  EXPECT_DOUBLE_EQ(modal["run_time_s"].get<double>(), 0.25);
  EXPECT_EQ(modal["notes"][0], "residual of every mode below 1e-9");
  ASSERT_EQ(modal["tables"].size(), 2u);
  const auto& modes = modal["tables"][0];
  EXPECT_EQ(modes["name"], "modes");
  EXPECT_EQ(modes["title"], "Natural frequencies");
  EXPECT_EQ(modes["file"], "modal/modes.csv");
  EXPECT_EQ(modes["rows"], 2);
  ASSERT_EQ(modes["columns"].size(), 3u);
  EXPECT_EQ(modes["columns"][1]["name"], "frequency_hz");
  EXPECT_EQ(modes["columns"][1]["unit"], "Hz");
  EXPECT_EQ(modes["columns"][1]["kind"], "number");
  EXPECT_EQ(modes["columns"][2]["kind"], "text");
  // Every file the manifest lists exists.
  for (const auto& a : m["analyses"])
    for (const auto& t : a["tables"])
      EXPECT_TRUE(fs::exists(outdir_ / t["file"].get<std::string>()));

  // The failed analysis is recorded with its status and message, even without tables.
  const auto& failed = m["analyses"][1];
  EXPECT_EQ(failed["name"], "unbalance");
  EXPECT_EQ(failed["status"], "singular");
  EXPECT_EQ(failed["message"], failed_output().message);
  EXPECT_TRUE(failed["tables"].empty());
}

TEST_F(ResultsWriterTest, AllOkMeansOverallOk) {
  write_results(outdir_, info_, {modal_output()}, "");
  const nlohmann::json m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["status"], "ok");
  EXPECT_TRUE(m["report"].is_null());
  EXPECT_FALSE(fs::exists(outdir_ / "report.html"));
}

TEST_F(ResultsWriterTest, GivenSha256IsKept) {
  info_.model_sha256 = sha256_hex("the model as it was read at the start");
  write_results(outdir_, info_, {modal_output()}, "");
  EXPECT_EQ(read_json(outdir_ / "manifest.json")["model"]["sha256"], info_.model_sha256);
}

TEST_F(ResultsWriterTest, ReplacesPreviousResultsCompletely) {
  write_results(outdir_, info_, {modal_output()}, "old report");
  AnalysisOutput other = failed_output();
  other.name = "other";
  write_results(outdir_, info_, {other}, "new report");
  EXPECT_FALSE(fs::exists(outdir_ / "modal"));  // nothing of the old run survives
  EXPECT_TRUE(fs::is_directory(outdir_ / "other"));
  EXPECT_EQ(read_text(outdir_ / "report.html"), "new report");
  EXPECT_EQ(read_json(outdir_ / "manifest.json")["analyses"][0]["name"], "other");
  EXPECT_TRUE(leftovers(outdir_).empty());
}

TEST_F(ResultsWriterTest, TrailingSeparatorStagesNextToTheFolder) {
  write_results(outdir_.string() + "/", info_, {modal_output()}, "");
  EXPECT_TRUE(fs::exists(outdir_ / "manifest.json"));
  EXPECT_TRUE(leftovers(outdir_).empty());
}

// Results are written as each analysis finishes; a run that ends with an error keeps what
// finished, in a folder whose manifest says it is incomplete and what did not run.
TEST_F(ResultsWriterTest, AnAbandonedRunKeepsWhatFinishedAndSaysItIsIncomplete) {
  {
    ResultsWriter writer(outdir_, info_);
    EXPECT_FALSE(fs::exists(outdir_));  // nothing on disk before begin
    writer.begin({"modal", "unbalance"});
    nlohmann::json m = read_json(outdir_ / "manifest.json");
    EXPECT_EQ(m["status"], "incomplete");
    EXPECT_EQ(m["complete"], false);
    EXPECT_EQ(m["not_run"], nlohmann::json({"modal", "unbalance"}));
    writer.add(modal_output());
    EXPECT_TRUE(fs::exists(outdir_ / "modal" / "modes.csv"));
    m = read_json(outdir_ / "manifest.json");
    EXPECT_EQ(m["analyses"].size(), 1u);
    EXPECT_EQ(m["not_run"], nlohmann::json({"unbalance"}));
    // An error in the middle of the run: a repeated analysis name.
    EXPECT_THROW(writer.add(modal_output()), std::invalid_argument);
  }
  const nlohmann::json m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["status"], "incomplete");
  EXPECT_EQ(m["complete"], false);
  EXPECT_NE(m["run_message"].get<std::string>().find("ended with an error"), std::string::npos);
  EXPECT_EQ(m["not_run"], nlohmann::json({"unbalance"}));
  ASSERT_EQ(m["analyses"].size(), 1u);
  EXPECT_EQ(m["analyses"][0]["name"], "modal");
  EXPECT_TRUE(fs::exists(outdir_ / "modal" / "modes.csv"));
  EXPECT_FALSE(fs::exists(outdir_ / "unbalance"));
  EXPECT_TRUE(leftovers(outdir_).empty());
  EXPECT_TRUE(hidden_entries(outdir_).empty());
}

// Until begin() the earlier results are untouched (bad input found before computing leaves
// them as they were); begin() replaces them.
TEST_F(ResultsWriterTest, EarlierResultsStayUntilTheRunBegins) {
  write_results(outdir_, info_, {modal_output()}, "old report");
  const std::string old_manifest = read_text(outdir_ / "manifest.json");
  {
    ResultsWriter writer(outdir_, info_);
    writer.check({"unbalance"});
  }  // destroyed before begin: as a run refused for bad input
  EXPECT_EQ(read_text(outdir_ / "manifest.json"), old_manifest);
  EXPECT_EQ(read_text(outdir_ / "report.html"), "old report");
  {
    ResultsWriter writer(outdir_, info_);
    writer.begin({"unbalance"});
    EXPECT_FALSE(fs::exists(outdir_ / "modal"));
    EXPECT_FALSE(fs::exists(outdir_ / "report.html"));
  }
  EXPECT_EQ(read_json(outdir_ / "manifest.json")["status"], "incomplete");
}

// A process killed in its last analysis keeps the analyses before it; the next run into the
// same folder replaces the killed run's results, including what it was writing at the kill.
TEST_F(ResultsWriterTest, AKilledRunKeepsItsFinishedAnalyses) {
  EXPECT_EXIT(
      {
        ResultsWriter writer(outdir_, info_);
        writer.begin({"modal", "unbalance"});
        writer.add(modal_output());
        writer.add_report("half");
        fs::create_directories(outdir_ / ".unbalance.tmp-999999");  // caught mid-write
        std::_Exit(3);  // no destructors, no commit: as if killed
      },
      ::testing::ExitedWithCode(3), "");
  nlohmann::json m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["status"], "incomplete");
  EXPECT_EQ(m["complete"], false);
  EXPECT_EQ(m["not_run"], nlohmann::json({"unbalance"}));
  EXPECT_EQ(m["report"], "report.html");
  EXPECT_TRUE(fs::exists(outdir_ / "modal" / "modes.csv"));
  EXPECT_EQ(read_text(outdir_ / "report.html"), "half");

  // Staging folders of earlier geardyn versions (a whole run next to OUTDIR) are removed when
  // their process is gone; one of a live process (pid 1 always exists) stays.
  fs::create_directories(base_ / "results.tmp-999999999");
  fs::create_directories(base_ / "results.tmp-1");
  AnalysisOutput other = failed_output();
  write_results(outdir_, info_, {other}, "");
  m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["status"], "failed");
  EXPECT_EQ(m["complete"], true);
  EXPECT_FALSE(fs::exists(outdir_ / "modal"));
  EXPECT_FALSE(fs::exists(outdir_ / "report.html"));
  EXPECT_TRUE(hidden_entries(outdir_).empty());
  EXPECT_EQ(leftovers(outdir_), std::vector<std::string>{"results.tmp-1"});
}

TEST_F(ResultsWriterTest, ASecondWriterOfTheSameFolderIsRefused) {
  // Two runs into one folder: the second is refused at once (not both "ok" with one run's
  // results gone); once the first is done, the folder is free again.
  {
    ResultsWriter first(outdir_, info_);
    try {
      ResultsWriter second(outdir_, info_);
      ADD_FAILURE() << "a second writer was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("another geardyn run"), std::string::npos) << e.what();
    }
    first.add(modal_output());
    first.commit();
  }
  EXPECT_TRUE(fs::exists(outdir_ / "manifest.json"));
  EXPECT_NO_THROW(write_results(outdir_, info_, {modal_output()}, ""));
}

TEST_F(ResultsWriterTest, RefusesToReplaceAForeignFolder) {
  fs::create_directories(outdir_);
  std::ofstream(outdir_ / "precious.txt") << "not geardyn's";
  try {
    write_results(outdir_, info_, {modal_output()}, "");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(outdir_.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(outdir_ / "precious.txt"));
  EXPECT_TRUE(leftovers(outdir_).empty());

  // A manifest.json that geardyn did not write does not make the folder replaceable either.
  std::ofstream(outdir_ / "manifest.json") << R"({"name": "some other tool"})";
  EXPECT_THROW(write_results(outdir_, info_, {modal_output()}, ""), std::runtime_error);
  EXPECT_TRUE(fs::exists(outdir_ / "precious.txt"));
}

// A rerun into an earlier results folder keeps what a user added there (a post-processing
// script) and says so; a user's entry where a new analysis would be written is refused before
// anything is removed.
TEST_F(ResultsWriterTest, ForeignFilesAreKeptAndNeverOverwritten) {
  write_results(outdir_, info_, {modal_output()}, "old report");
  std::ofstream(outdir_ / "post.py") << "import pandas\n";
  fs::create_directories(outdir_ / "unbalance");
  std::ofstream(outdir_ / "unbalance" / "notes.txt") << "mine";
  try {
    write_results(outdir_, info_, {failed_output()}, "");  // named "unbalance"
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'unbalance'"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(outdir_ / "modal" / "modes.csv"));  // nothing removed
  EXPECT_EQ(read_text(outdir_ / "unbalance" / "notes.txt"), "mine");

  AnalysisOutput other = modal_output();
  other.name = "other";
  {
    ResultsWriter writer(outdir_, info_);
    writer.begin({"other"});
    writer.add(other);
    writer.commit();
    EXPECT_EQ(writer.kept_files(), (std::vector<std::string>{"post.py", "unbalance"}));
  }
  EXPECT_EQ(read_text(outdir_ / "post.py"), "import pandas\n");
  EXPECT_FALSE(fs::exists(outdir_ / "modal"));
  const nlohmann::json m = read_json(outdir_ / "manifest.json");
  EXPECT_EQ(m["kept_files"], nlohmann::json({"post.py", "unbalance"}));
  // Kept files are not the run's: the next run keeps them again, and removes "other".
  write_results(outdir_, info_, {modal_output()}, "");
  EXPECT_TRUE(fs::exists(outdir_ / "post.py"));
  EXPECT_FALSE(fs::exists(outdir_ / "other"));
}

TEST_F(ResultsWriterTest, ReplacesAnEmptyFolder) {
  fs::create_directories(outdir_);
  write_results(outdir_, info_, {modal_output()}, "");
  EXPECT_TRUE(fs::exists(outdir_ / "manifest.json"));
}

TEST_F(ResultsWriterTest, RejectsNamesThatAreNotFolderNames) {
  for (const std::string name :
       {"", ".", "..", "../escape", "a/b", "manifest.json", "report.html"}) {
    AnalysisOutput out = modal_output();
    out.name = name;
    EXPECT_THROW(write_results(outdir_, info_, {out}, ""), std::invalid_argument) << name;
  }
  AnalysisOutput out = modal_output();
  EXPECT_FALSE(fs::exists(outdir_));  // analysis names are checked before anything is written
  out.tables[1].name = "../../escape";
  EXPECT_THROW(write_results(outdir_, info_, {out}, ""), std::invalid_argument);
  out.tables[1].name = out.tables[0].name;
  EXPECT_THROW(write_results(outdir_, info_, {out}, ""), std::invalid_argument);
  EXPECT_FALSE(fs::exists(base_ / "escape"));
  EXPECT_FALSE(fs::exists(outdir_ / "modal"));  // the analysis was not written in part
  EXPECT_TRUE(read_json(outdir_ / "manifest.json")["analyses"].empty());
  EXPECT_TRUE(hidden_entries(outdir_).empty());
  EXPECT_TRUE(leftovers(outdir_).empty());
}

TEST_F(ResultsWriterTest, MissingModelFileNamesThePath) {
  info_.model_path = base_ / "no-such-model.toml";
  try {
    write_results(outdir_, info_, {modal_output()}, "");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-model.toml"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(outdir_));
}

}  // namespace
}  // namespace geardyn::io
