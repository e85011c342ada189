#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace geardyn::app {

struct RunOptions {
  std::string model_path;
  std::string output_dir;
  std::vector<std::string> overrides;
  std::vector<std::string> only;
  bool quiet = false;
};

/// The results folder of `run` without -o: results/<model file name>, or results/<folder> for a
/// file named model.toml (the examples), so models never share it by their common file name.
std::filesystem::path default_output_dir(const std::string& model_path);

/// Each returns the process exit code (0 ok, 1 numerical failure, 2 bad input); InputError
/// propagates to main, which prints it and returns 2.
int command_run(const RunOptions& options, int argc, char** argv);
int command_check(const std::string& model_path, const std::vector<std::string>& overrides);
int command_schema();

}  // namespace geardyn::app
