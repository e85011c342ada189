// order_analysis: reading the record file (CSV with a header row, or geardyn's time_history.h5)
// and building the analysed shaft's angle from an angle or a tacho column, with located errors.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/analyses/order_analysis.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/text.hpp"
#include "geardyn/io/time_history_h5.hpp"
#include "geardyn/signal/order_tracking.hpp"

namespace geardyn::analyses {
namespace {

std::string trim(std::string s) {
  const auto a = s.find_first_not_of(" \t\r\"");
  if (a == std::string::npos) return {};
  const auto b = s.find_last_not_of(" \t\r\"");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) out.push_back(trim(field));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool parse_double(const std::string& s, double& v) {
  if (s == "nan" || s == "NaN") {
    v = std::nan("");
    return true;
  }
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, v);
  return ec == std::errc() && p == end;
}

OrderRecord read_csv(const std::filesystem::path& path, const Context& context) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw context.error("record_file", "a readable record file (relative to the model file)",
                        fmt::format("{} (cannot be opened)", path.string()));
  OrderRecord r;
  r.path = path;
  std::stringstream in(*text);
  std::string line;
  int line_no = 0;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty() || line[0] == '#') continue;
    std::vector<std::string> fields = split(line);
    if (r.names.empty()) {
      r.names = fields;
      continue;
    }
    if (fields.size() != r.names.size())
      throw InputError(SourceLocation{path.string(), line_no, 1}, context.key("record_file"),
                       fmt::format("{} comma-separated values (as the header)", r.names.size()),
                       fmt::format("{} values", fields.size()));
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c)
      if (!parse_double(fields[c], row[c])) row[c] = std::nan("");  // a text column
    rows.push_back(std::move(row));
    r.line.push_back(line_no);
  }
  if (r.names.empty() || rows.size() < 4)
    throw InputError(SourceLocation{path.string(), line_no, 0}, context.key("record_file"),
                     "a header row and at least 4 data rows", fmt::format("{} rows", rows.size()));
  r.values.resize(static_cast<Eigen::Index>(rows.size()),
                  static_cast<Eigen::Index>(r.names.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t c = 0; c < r.names.size(); ++c)
      r.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = rows[i][c];
  return r;
}

OrderRecord read_h5(const std::filesystem::path& path, const Context& context) {
  io::TimeHistory h;
  try {
    h = io::read_time_history_h5(path);
  } catch (const std::exception& e) {
    throw context.error("record_file", "a geardyn time_history.h5 file", e.what());
  }
  OrderRecord r;
  r.path = path;
  r.names.push_back("time_s");
  for (const io::TimeHistoryChannel& c : h.channels) r.names.push_back(c.name);
  const auto n = static_cast<Eigen::Index>(h.time.size());
  r.values.resize(n, h.values.cols() + 1);
  r.values.col(0) = Eigen::Map<const Eigen::VectorXd>(h.time.data(), n);
  r.values.rightCols(h.values.cols()) = h.values.topRows(n);
  r.line.assign(static_cast<std::size_t>(n), 0);
  return r;
}

Eigen::Index column_of(const OrderRecord& r, const std::string& name, const std::string& key,
                       const Context& context) {
  const auto it = std::find(r.names.begin(), r.names.end(), name);
  if (it == r.names.end()) {
    std::string list;
    for (const std::string& n : r.names) list += (list.empty() ? "" : ", ") + n;
    throw context.error(key, fmt::format("a column of {}", r.path.filename().string()),
                        fmt::format("\"{}\" (the columns are: {})", name, list));
  }
  return static_cast<Eigen::Index>(it - r.names.begin());
}

// Located at the record file's line of sample j (or at the key for an HDF5 record).
InputError at_sample(const OrderRecord& r, Eigen::Index j, const std::string& key,
                     const Context& context, std::string expected, std::string found) {
  const int line = r.line.empty() ? 0 : r.line[static_cast<std::size_t>(j)];
  if (line > 0)
    return InputError(SourceLocation{r.path.string(), line, 0}, context.key(key),
                      std::move(expected), std::move(found));
  return context.error(key, std::move(expected),
                       fmt::format("{} at sample {}", std::move(found), j));
}

}  // namespace

OrderRecord read_order_record(const model::Model& model, const OrderAnalysisSettings& s,
                              const Context& context) {
  namespace fs = std::filesystem;
  const fs::path path = resolve_model_path(model, s.record_file);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw context.error("record_file",
                        "a readable record file, CSV or time_history.h5 (relative to the model "
                        "file)",
                        fmt::format("\"{}\" ({} does not exist)", s.record_file, path.string()));
  return path.extension() == ".h5" ? read_h5(path, context) : read_csv(path, context);
}

OrderReference order_reference(const OrderRecord& r, const OrderAnalysisSettings& s,
                               const Context& context) {
  OrderReference ref;
  const Eigen::Index tc = column_of(r, s.time_column, "time_column", context);
  ref.time = r.values.col(tc);
  for (Eigen::Index j = 0; j < ref.time.size(); ++j) {
    if (!std::isfinite(ref.time[j]))
      throw at_sample(r, j, "time_column", context, "a finite time [s]", "not a number");
    if (j > 0 && !(ref.time[j] > ref.time[j - 1]))
      throw at_sample(r, j, "time_column", context, "strictly increasing time",
                      fmt::format("{:.9g} s after {:.9g} s", ref.time[j], ref.time[j - 1]));
  }
  try {
    (void)signal::uniform_sample_rate(ref.time);
  } catch (const std::invalid_argument& e) {
    throw context.error("time_column", "a uniformly sampled time column", e.what(),
                        "resample the record to a constant sample rate");
  }
  const bool by_angle = !s.angle_column.empty();
  const std::string key = by_angle ? "angle_column" : "tacho_column";
  const Eigen::Index rc = column_of(r, by_angle ? s.angle_column : s.tacho_column, key, context);
  ref.reference_column = rc;
  const Eigen::VectorXd v = r.values.col(rc);
  ref.first = 0;
  ref.last = v.size() - 1;
  if (by_angle) {
    for (Eigen::Index j = 1; j < v.size(); ++j)
      if (!(v[j] > v[j - 1]))
        throw at_sample(r, j, key, context, "a shaft angle [rad] that increases",
                        fmt::format("{:.9g} rad after {:.9g} rad", v[j], v[j - 1]));
    ref.angle = s.shaft_ratio * v;
    ref.description = fmt::format("angle column \"{}\"", s.angle_column);
  } else {
    if (!v.allFinite())
      throw context.error(key, "a tacho column of finite numbers", "non-numeric values");
    const double threshold =
        std::isnan(s.tacho_threshold) ? 0.5 * (v.minCoeff() + v.maxCoeff()) : s.tacho_threshold;
    Eigen::VectorXd pulses;
    try {
      pulses = signal::tacho_pulse_times(ref.time, v, threshold);
    } catch (const std::invalid_argument&) {
      pulses.resize(0);
    }
    if (pulses.size() < 2)
      throw context.error(
          key,
          "a tacho signal with at least 2 pulses (rising through the "
          "threshold)",
          fmt::format("{} pulses through threshold {:.6g}", pulses.size(), threshold),
          "check tacho_column and tacho_threshold");
    ref.angle =
        s.shaft_ratio * signal::angle_from_pulse_times(ref.time, pulses, s.pulses_per_revolution);
    while (ref.first < v.size() && ref.time[ref.first] < pulses[0]) ++ref.first;
    while (ref.last > 0 && ref.time[ref.last] > pulses[pulses.size() - 1]) --ref.last;
    ref.description = fmt::format(
        "tacho column \"{}\" ({} pulses, {} per revolution, threshold {:.6g}; samples before the "
        "first and after the last pulse are not analysed)",
        s.tacho_column, pulses.size(), s.pulses_per_revolution, threshold);
  }
  if (s.shaft_ratio != 1.0)
    ref.description += fmt::format(", times shaft ratio {:.6g}", s.shaft_ratio);
  return ref;
}

std::vector<Eigen::Index> order_channels(const OrderRecord& r, const OrderAnalysisSettings& s,
                                         const OrderReference& ref, const Context& context) {
  std::vector<Eigen::Index> out;
  if (!s.channels.empty()) {
    for (const std::string& c : s.channels) out.push_back(column_of(r, c, "channels", context));
  } else {
    const Eigen::Index tc = column_of(r, s.time_column, "time_column", context);
    for (Eigen::Index c = 0; c < r.values.cols(); ++c)
      if (c != tc && c != ref.reference_column && r.values.col(c).allFinite()) out.push_back(c);
  }
  for (Eigen::Index c : out)
    for (Eigen::Index j = 0; j < r.values.rows(); ++j)
      if (!std::isfinite(r.values(j, c)))
        throw at_sample(
            r, j, "channels", context,
            fmt::format("a number in column \"{}\"", r.names[static_cast<std::size_t>(c)]),
            "a value that is not a number");
  if (out.empty())
    throw context.error("channels", "at least one numeric column besides time and reference",
                        "none");
  return out;
}

}  // namespace geardyn::analyses
