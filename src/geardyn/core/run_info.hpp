#pragma once
// What a run of geardyn records about itself: shared by the results writer (manifest.json) and
// the HTML report header, which depend on core only.
#include <chrono>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

namespace geardyn {

struct RunInfo {
  std::filesystem::path model_path;  ///< the model file as given on the command line
  /// Hex SHA-256 of the model file as read. If empty, the results writer computes it from
  /// `model_path` (when that is not empty).
  std::string model_sha256;
  std::string command_line;  ///< argv joined by spaces
  std::string model_title;   ///< the model's `title` ("" when it has none): the report's heading
  /// Analyses selected to run that have not finished yet. Not empty in the report and manifest
  /// written while the run is in progress (a run killed then leaves them saying so).
  std::vector<std::string> not_run;
  /// When the run started; defaults to the moment the RunInfo is made.
  std::chrono::system_clock::time_point start_time = std::chrono::system_clock::now();
};

/// `t` as UTC ISO 8601 to the second, e.g. "2025-01-31T17:04:05Z".
inline std::string format_utc_iso8601(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char buffer[32];
  const std::size_t n = std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return std::string(buffer, n);
}

}  // namespace geardyn
