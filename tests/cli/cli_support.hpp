#pragma once
// Helpers of the end-to-end tests: run the geardyn program, read the CSV and JSON it writes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace geardyn::cli_test {

namespace fs = std::filesystem;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline const std::string kExe = GEARDYN_EXE;
inline const std::string kSource = GEARDYN_SOURCE_DIR;

struct ProcessResult {
  int exit_code = -1;
  std::string out, err;
};

inline ProcessResult run(const std::string& args) {
  const fs::path err_file =
      fs::temp_directory_path() / ("geardyn_cli_err_" + std::to_string(::getpid()));
  const std::string command = kExe + " " + args + " 2> " + err_file.string();
  ProcessResult r;
  FILE* pipe = ::popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr);
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  fs::remove(err_file);
  return r;
}

inline fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "cli" / "runs" / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

// Minimal CSV reader: the files geardyn writes have a header row and no quoted commas in the
// columns read here.
inline std::map<std::string, std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  std::map<std::string, std::vector<std::string>> columns;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::size_t j = 0;
    for (std::string cell; std::getline(ls, cell, ',') && j < header.size(); ++j)
      columns[header[j]].push_back(cell);
  }
  return columns;
}

inline nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace geardyn::cli_test
