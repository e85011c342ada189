// End-to-end tests of the geardyn program: the examples reproduce their published numbers from
// the CSV files they write; exit codes (0 ok, 1 numerical failure, 2 bad input); bad input
// leaves no results folder; a numerical failure leaves a manifest that says so; a killed run
// keeps its finished analyses; a second run into a folder in use is refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "geardyn/io/sha256.hpp"

namespace {

using namespace geardyn::cli_test;

// Lateral natural frequencies |lambda| [rad/s] from a modes.csv, in table order.
std::vector<double> lateral_rad_s(const fs::path& csv) {
  auto c = read_csv(csv);
  std::vector<double> out;
  for (std::size_t i = 0; i < c["kind"].size(); ++i)
    if (c["kind"][i] == "lateral") out.push_back(kTwoPi * std::stod(c["frequency_hz"][i]));
  return out;
}

TEST(Cli, VersionAndHelp) {
  const ProcessResult v = run("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("geardyn 0."), std::string::npos) << v.out;
  EXPECT_EQ(run("--help").exit_code, 0);
  EXPECT_EQ(run("").exit_code, 2);            // a sub-command is required
  EXPECT_EQ(run("frobnicate").exit_code, 2);  // unknown sub-command
}

TEST(Cli, SchemaIsTheCheckedInModelReference) {
  const ProcessResult s = run("schema");
  ASSERT_EQ(s.exit_code, 0);
  std::ifstream in(kSource + "/docs/model-reference.md");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_TRUE(s.out == ss.str())
      << "docs/model-reference.md differs from `geardyn schema`: regenerate it with "
         "GEARDYN_UPDATE_DOCS=1 build/tests/model/test_model --gtest_filter='ModelReference.*'";
}

// Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines (CUP 2010), Example 5.9.1.
// The book prints |lambda| to 3 decimals; 1e-3 relative (the tolerance) is far above
// the discretisation-consistent agreement (the model is the book's 6-element model).
TEST(Cli, FriswellExample591ReproducesTheBook) {
  const fs::path out = fresh_dir("friswell");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/friswell_5_9_1/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> at0 = {86.658, 86.658, 274.313, 274.313, 716.786, 716.786};
  const std::vector<double> at4000 = {85.389, 87.796, 251.785, 294.713, 600.179, 827.075};
  const auto f0 = lateral_rad_s(out / "modes_0rpm" / "modes.csv");
  const auto f4 = lateral_rad_s(out / "modes_4000rpm" / "modes.csv");
  ASSERT_GE(f0.size(), 6u);
  ASSERT_GE(f4.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(f0[i], at0[i], 1e-3 * at0[i]) << "0 rpm, mode " << i + 1;
    EXPECT_NEAR(f4[i], at4000[i], 1e-3 * at4000[i]) << "4000 rpm, mode " << i + 1;
  }
  // The free-free torsional mode of the 6-DOF-per-node model.
  auto c = read_csv(out / "modes_0rpm" / "modes.csv");
  bool torsional = false;
  for (std::size_t i = 0; i < c["kind"].size(); ++i)
    if (c["kind"][i] == "torsional" && std::stod(c["frequency_hz"][i]) > 1.0) {
      EXPECT_NEAR(kTwoPi * std::stod(c["frequency_hz"][i]), 650.408, 1e-3 * 650.408);
      torsional = true;
      break;
    }
  EXPECT_TRUE(torsional);

  const auto manifest = read_json(out / "manifest.json");
  EXPECT_EQ(manifest["status"], "ok");
  EXPECT_EQ(manifest["model"]["sha256"],
            geardyn::io::sha256_file(kSource + "/examples/friswell_5_9_1/model.toml"));
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_TRUE(fs::exists(out / "campbell" / "critical_speeds.csv"));
}

// The geared rotor of J. Hong, L. Jiang, X. Xu, Y. Ma, "High cycle fatigue failure with radial
// cracks in gears of aero-engines", Chinese Journal of Aeronautics, 2020: the unbalance on the HPR
// reaches the driven gear's swing only through the mesh. Their Fig. 18 shows the swing
// response vanishing for weak meshes (below ~1e5 N/m); with k_mesh = 1 N/m the swing must be
// at least 1e4 times smaller than at the design value 1e7 N/m (it scales with k for k -> 0).
TEST(Cli, GearedRotorDemoRunsAndTheMeshCarriesTheSwing) {
  const fs::path out = fresh_dir("geared_rotor");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/geared_rotor_hcf/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto manifest = read_json(out / "manifest.json");
  EXPECT_EQ(manifest["status"], "ok");
  EXPECT_GE(manifest["analyses"].size(), 9u);
  for (const auto& a : manifest["analyses"]) EXPECT_EQ(a["status"], "ok") << a["name"];

  auto sweep = read_csv(out / "sweep_mesh_stiffness" / "sweep.csv");
  const auto& k = sweep["value_N_m"];  // the swept key's unit in the name
  const auto& amp = sweep["swing_amplitude_rad"];
  ASSERT_FALSE(k.empty());
  double at_weak = NAN, at_design = NAN;
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (std::abs(std::stod(k[i]) - 1.0) < 1e-9) at_weak = std::stod(amp[i]);
    if (std::abs(std::stod(k[i]) - 1e7) < 1e-3) at_design = std::stod(amp[i]);
  }
  ASSERT_FALSE(std::isnan(at_weak));
  ASSERT_FALSE(std::isnan(at_design));
  EXPECT_LT(at_weak, 1e-4 * at_design);
  EXPECT_TRUE(fs::exists(out / "transient_36900rpm" / "time_history.csv"));

  // Hong et al. (2020), Table 3: without the mesh the HPR modes carry no swing of the driven gear;
  // with the mesh some of them do. HPR modes: the turbine disk moves (relative amplitude
  // > 0.1). "No swing": below 1e-9 (round-off of the eigenvectors); "carries": above 1e-3.
  auto count_hpr_modes_with_swing = [](const fs::path& csv, double threshold, int& hpr_modes) {
    auto c = read_csv(csv);
    int with_swing = 0;
    hpr_modes = 0;
    for (std::size_t i = 0; i < c["mode"].size(); ++i) {
      if (std::stod(c["turbine_x_relative"][i]) < 0.1) continue;
      ++hpr_modes;
      if (std::stod(c["swing_relative"][i]) > threshold) ++with_swing;
    }
    return with_swing;
  };
  int hpr_uncoupled = 0, hpr_coupled = 0;
  EXPECT_EQ(
      count_hpr_modes_with_swing(out / "modes_without_mesh" / "modes.csv", 1e-9, hpr_uncoupled), 0);
  EXPECT_GT(hpr_uncoupled, 0);
  EXPECT_GT(count_hpr_modes_with_swing(out / "modes" / "modes.csv", 1e-3, hpr_coupled), 0);
}

TEST(Cli, UnknownKeyIsBadInputWithLocationAndSuggestion) {
  const fs::path out = fresh_dir("typo");
  const ProcessResult r = run("run " + kSource + "/tests/cli/data/typo.toml -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("typo.toml:13:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("lenght"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'length'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "bad input must not leave a results folder";
}

TEST(Cli, UndefinedNodeIsBadInput) {
  const ProcessResult r = run("check " + kSource + "/tests/cli/data/undefined_node.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bearings[0].node"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("s.7"), std::string::npos) << r.err;
}

TEST(Cli, MissingFileAndBadOverrideAreBadInput) {
  EXPECT_EQ(run("check /nonexistent/model.toml").exit_code, 2);
  const ProcessResult r =
      run("check " + kSource + "/examples/friswell_5_9_1/model.toml --set bearings[0].kxx=-5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bearings[0].kxx"), std::string::npos) << r.err;
  const ProcessResult ok =
      run("check " + kSource + "/examples/friswell_5_9_1/model.toml --set bearings[0].kxx=2e6");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(Cli, AnOutputThatCannotBeReplacedIsRefusedBeforeAnythingRuns) {
  // -o naming a file, or a folder with a user's files and no geardyn manifest: bad input (exit
  // 2) found before any analysis computes, and what is there stays untouched.
  const fs::path base = fresh_dir("refused_output");
  fs::create_directories(base);
  const fs::path file = base / "results.txt";
  std::ofstream(file) << "a user's file\n";
  const fs::path folder = base / "postprocessing";
  fs::create_directories(folder);
  std::ofstream(folder / "plot.py") << "print('mine')\n";
  const std::string model = kSource + "/examples/friswell_5_9_1/model.toml";
  for (const fs::path& out : {file, folder}) {
    const ProcessResult r = run("run " + model + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--output"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("[modal]"), std::string::npos) << "an analysis ran: " << r.out;
  }
  EXPECT_TRUE(fs::is_regular_file(file));
  EXPECT_TRUE(fs::is_regular_file(folder / "plot.py"));
  for (const auto& entry : fs::directory_iterator(base))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos)
        << "staging folder left: " << entry.path();
}

TEST(Cli, TheDefaultResultsFolderIsNamedByTheModelsFolder) {
  // Every example is a model.toml: without -o, results/<its folder>, not results/model for all.
  const fs::path expected = fs::current_path() / "results" / "friswell_5_9_1";
  fs::remove_all(expected);
  const ProcessResult r =
      run("run " + kSource + "/examples/friswell_5_9_1/model.toml --only modes_0rpm -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(expected / "manifest.json")) << r.out;
  EXPECT_EQ(r.out, "") << "-q: errors only";
  EXPECT_FALSE(fs::exists(fs::current_path() / "results" / "model"));
  fs::remove_all(expected);
}

TEST(Cli, EachAnalysisIsAnnouncedAsItStarts) {
  const fs::path out = fresh_dir("announced");
  const ProcessResult r = run("run " + kSource + "/examples/friswell_5_9_1/model.toml -o " +
                              out.string() + " --only modes_0rpm modes_4000rpm");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("analysis 1/2: modes_0rpm (modal)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("analysis 2/2: modes_4000rpm (modal)"), std::string::npos) << r.err;
}

TEST(Cli, SkippedNastranCardsAreWarnedOnTheTerminal) {
  const fs::path out = fresh_dir("skipped_card");
  const ProcessResult r =
      run("run " + kSource + "/tests/cli/data/skipped_card.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: solid 'deck': "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("brick_with_shell.bdf:15: unsupported Nastran entry CQUAD4 skipped"),
            std::string::npos)
      << r.err;
}

TEST(Cli, ADeckWithoutElementsIsBadInputForCheckAndRun) {
  // Once an internal eigen-solver message at '<model>'; now located at the solid's file key.
  const std::string model = kSource + "/tests/cli/data/no_elements.toml";
  const fs::path out = fresh_dir("no_elements");
  for (const std::string& command : {"check " + model, "run " + model + " -o " + out.string()}) {
    const ProcessResult r = run(command);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("no_elements.toml"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("solids[0].file"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("grids_only.bdf' with 8 nodes"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

// Starts geardyn in the background (stdout and stderr to files in `dir`); returns its pid.
pid_t start(const std::vector<std::string>& args, const fs::path& dir) {
  fs::create_directories(dir);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
    if (std::freopen(out.c_str(), "w", stdout) == nullptr ||
        std::freopen(err.c_str(), "w", stderr) == nullptr)
      std::_Exit(127);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kExe.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(kExe.c_str(), argv.data());
    std::_Exit(127);
  }
  return pid;
}

// Waits (up to `seconds`) until `done()` holds; false on time-out.
template <class Done>
bool wait_until(Done done, double seconds) {
  for (int i = 0; i < static_cast<int>(seconds * 20); ++i) {
    if (done()) return true;
    ::usleep(50000);
  }
  return done();
}

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// The manifest lists `analysis` as written (it is rewritten atomically after each analysis).
bool manifest_lists(const fs::path& out, const std::string& analysis) {
  std::ifstream in(out / "manifest.json");
  if (!in) return false;
  const auto m = nlohmann::json::parse(in, nullptr, false);
  if (!m.is_object() || !m.contains("analyses")) return false;
  for (const auto& a : m["analyses"])
    if (a["name"] == analysis) return true;
  return false;
}

TEST(Cli, AKilledRunKeepsItsFinishedAnalysesAndTheRerunReplacesThem) {
  // The second analysis (a 100 s transient, minutes of work) is killed; the first stays, in a
  // folder whose manifest and report say the run is incomplete. A rerun then writes a complete
  // folder over it and removes what the killed run was writing.
  const fs::path base = fresh_dir("killed");
  const fs::path out = base / "results";
  const std::string model = kSource + "/tests/cli/data/long_second_analysis.toml";
  const pid_t pid =
      start({"run", model, "-o", out.string(), "-q", "--set", "analyses[1].duration=100"},
            base / "first");
  ASSERT_TRUE(wait_until([&] { return manifest_lists(out, "modes"); }, 60.0));
  ::usleep(300000);  // well inside the transient
  ::kill(pid, SIGKILL);
  EXPECT_EQ(wait_exit(pid), -SIGKILL);

  auto m = read_json(out / "manifest.json");
  EXPECT_EQ(m["status"], "incomplete");
  EXPECT_EQ(m["complete"], false);
  EXPECT_EQ(m["not_run"], nlohmann::json({"run_up"}));
  ASSERT_EQ(m["analyses"].size(), 1u);
  EXPECT_EQ(m["analyses"][0]["name"], "modes");
  EXPECT_TRUE(fs::exists(out / "modes" / "modes.csv"));
  EXPECT_FALSE(fs::exists(out / "run_up"));
  std::ifstream report(out / "report.html");
  std::stringstream html;
  html << report.rdbuf();
  EXPECT_NE(html.str().find("incomplete: 1 of 2 analyses finished"), std::string::npos);

  const ProcessResult rerun =
      run("run " + model + " -o " + out.string() + " -q --set analyses[1].duration=0.01");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  m = read_json(out / "manifest.json");
  EXPECT_EQ(m["status"], "ok");
  EXPECT_EQ(m["complete"], true);
  EXPECT_TRUE(m["not_run"].empty());
  EXPECT_TRUE(fs::exists(out / "run_up"));
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().filename().string().front(), '.') << "left: " << entry.path();
}

TEST(Cli, ASecondRunIntoTheSameFolderIsRefusedWhileTheFirstRuns) {
  const fs::path base = fresh_dir("concurrent");
  const fs::path out = base / "results";
  const std::string model = kSource + "/tests/cli/data/long_second_analysis.toml";
  const pid_t first = start(
      {"run", model, "-o", out.string(), "-q", "--set", "analyses[1].duration=3"}, base / "first");
  ASSERT_TRUE(wait_until([&] { return manifest_lists(out, "modes"); }, 60.0));
  const ProcessResult second = run("run " + model + " -o " + out.string() + " -q");
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find("another geardyn run"), std::string::npos) << second.err;
  EXPECT_EQ(wait_exit(first), 0);
  const auto m = read_json(out / "manifest.json");  // the first run's results, complete
  EXPECT_EQ(m["status"], "ok");
  EXPECT_EQ(m["analyses"].size(), 2u);
  EXPECT_TRUE(fs::exists(out / "run_up"));
}

TEST(Cli, ARerunKeepsTheUsersFilesInTheResultsFolderAndSaysSo) {
  const fs::path out = fresh_dir("kept_files");
  const std::string model = kSource + "/examples/friswell_5_9_1/model.toml";
  ASSERT_EQ(run("run -q " + model + " --only modes_0rpm -o " + out.string()).exit_code, 0);
  std::ofstream(out / "post.py") << "print('mine')\n";
  const ProcessResult r = run("run " + model + " --only modes_0rpm -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("kept 'post.py'"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out / "post.py"));
  EXPECT_EQ(read_json(out / "manifest.json")["kept_files"], nlohmann::json({"post.py"}));
}

TEST(Cli, SingularFrfFailsNumericallyAndTheManifestSaysSo) {
  const fs::path out = fresh_dir("singular");
  const ProcessResult r =
      run("run -q " + kSource + "/tests/cli/data/free_rotor_frf.toml -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("frf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rigid-body"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(out / "manifest.json"));
  const auto manifest = read_json(out / "manifest.json");
  EXPECT_EQ(manifest["status"], "failed");
  EXPECT_NE(manifest["analyses"][0]["status"], "ok");
}

}  // namespace
