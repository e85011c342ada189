#include "geardyn/io/results_writer.hpp"

#include <fcntl.h>  // AT_FDCWD for renameat2
#include <fmt/format.h>
#include <signal.h>    // kill(pid, 0): is the process that made a staging folder alive?
#include <sys/file.h>  // flock: one writer per results folder
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "geardyn/core/version.hpp"
#include "geardyn/io/csv_writer.hpp"
#include "geardyn/io/sha256.hpp"

namespace geardyn::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kManifestName = "manifest.json";
constexpr const char* kReportName = "report.html";

// `outdir` + suffix, as a sibling of outdir (trailing separators dropped first, so that
// "results/" gives "results.tmp-123" and not "results/.tmp-123").
fs::path sibling(const fs::path& outdir, const std::string& suffix) {
  fs::path base = outdir;
  if (!base.has_filename()) base = base.parent_path();
  return base.parent_path() / (base.filename().string() + suffix);
}

std::string errno_text(int error) { return std::strerror(error); }

// Removes the staging folders `OUTDIR.tmp-<pid>` that runs killed before their commit left
// behind: those of processes that no longer exist (a live one may be another run writing).
// Best effort: what cannot be removed stays, and the run goes on.
void remove_stale_staging(const fs::path& outdir) {
  const fs::path any = sibling(outdir, ".tmp-");
  const fs::path parent = any.parent_path().empty() ? fs::path(".") : any.parent_path();
  const std::string prefix = any.filename().string();
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const auto pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid()) continue;                      // ours: handled by the caller
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    std::error_code remove_ec;
    fs::remove_all(it->path(), remove_ec);
  }
}

void write_file(const fs::path& file, std::string_view contents) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(fmt::format("cannot create '{}'", file.string()));
  out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("cannot write '{}'", file.string()));
}

// A name used as one path component: no separators, no "." / "..", nothing that collides with
// the files at the top of the results folder.
void check_component(const std::string& name, const char* what) {
  std::string problem;
  if (name.empty())
    problem = "it is empty";
  else if (name == "." || name == "..")
    problem = "it is a relative folder reference";
  else if (name.find_first_of(std::string("/\\\0", 3)) != std::string::npos)
    problem = "it contains a path separator or NUL";
  else
    for (unsigned char c : name)
      if (c < 0x20) problem = "it contains a control character";
  if (!problem.empty())
    throw std::invalid_argument(fmt::format(
        "{} '{}' cannot be used as a file name in the results folder: {}", what, name, problem));
}

}  // namespace

bool is_replaceable_results_dir(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir, ec);
  if (status.type() == fs::file_type::not_found) return true;
  if (ec || status.type() != fs::file_type::directory) return false;
  if (fs::is_empty(dir, ec) && !ec) return true;
  std::ifstream in(dir / kManifestName);
  if (!in) return false;
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  return manifest.is_object() && manifest.contains("geardyn_version");
}

ResultsWriter::ResultsWriter(fs::path outdir, RunInfo info)
    : outdir_(std::move(outdir)), info_(std::move(info)) {
  if (outdir_.empty()) throw std::invalid_argument("results folder: empty path");
  staging_ = sibling(outdir_, fmt::format(".tmp-{}", ::getpid()));
  if (!is_replaceable_results_dir(outdir_))
    throw std::runtime_error(fmt::format(
        "results folder '{}' exists and is not a geardyn results folder (not a folder, or not "
        "empty and without a geardyn manifest.json); refusing to replace it: choose another "
        "output folder or remove it",
        outdir_.string()));
  if (info_.model_sha256.empty() && !info_.model_path.empty())
    info_.model_sha256 = sha256_file(info_.model_path);

  lock_outdir();
  try {
    remove_stale_staging(outdir_);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(staging_, ec))) {
      fs::remove_all(staging_, ec);  // left by an earlier process with our pid
      if (ec)
        throw std::runtime_error(fmt::format("cannot remove the leftover staging folder '{}': {}",
                                             staging_.string(), ec.message()));
    }
    fs::create_directories(staging_, ec);
    if (ec)
      throw std::runtime_error(fmt::format("cannot create the staging folder '{}': {}",
                                           staging_.string(), ec.message()));
  } catch (...) {
    ::close(lock_fd_);  // no destructor runs for a constructor that throws
    throw;
  }
}

void ResultsWriter::lock_outdir() {
  const fs::path lock = sibling(outdir_, "");
  const fs::path file = lock.parent_path() / ("." + lock.filename().string() + ".lock");
  std::error_code ec;
  if (!file.parent_path().empty()) fs::create_directories(file.parent_path(), ec);
  if (ec)
    throw std::runtime_error(fmt::format("cannot create the folder '{}': {}",
                                         file.parent_path().string(), ec.message()));
  lock_fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0)
    throw std::runtime_error(
        fmt::format("cannot create the lock file '{}': {}", file.string(), errno_text(errno)));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw std::runtime_error(fmt::format(
        "results folder '{}' is being written by another geardyn run ({}: {}); wait for it "
        "to finish or choose another output folder",
        outdir_.string(), file.string(), error == EWOULDBLOCK ? "locked" : errno_text(error)));
  }
}

ResultsWriter::~ResultsWriter() {
  if (!committed_ && !keep_staging_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);  // best effort: a destructor must not throw
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void ResultsWriter::add(const AnalysisOutput& output) {
  if (committed_) throw std::logic_error("ResultsWriter::add after commit");
  check_component(output.name, "analysis name");
  if (output.name == kManifestName || output.name == kReportName)
    throw std::invalid_argument(
        fmt::format("analysis name '{}' is reserved in the results folder", output.name));
  for (const auto& a : analyses_)
    if (a.name == output.name)
      throw std::invalid_argument(fmt::format("analysis name '{}' repeats", output.name));

  AnalysisRecord record;
  record.name = output.name;
  record.type = output.type;
  record.status = std::string(to_string(output.status));
  record.message = output.message;
  record.run_time_s = output.run_time_s;
  record.notes = output.notes;

  const fs::path folder = staging_ / output.name;
  std::error_code ec;
  fs::create_directory(folder, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot create the folder '{}': {}", folder.string(), ec.message()));

  std::set<std::string> table_names;
  for (const Table& table : output.tables) {
    check_component(table.name, "table name");
    if (!table_names.insert(table.name).second)
      throw std::invalid_argument(
          fmt::format("analysis '{}': table name '{}' repeats", output.name, table.name));
    const std::string file_name = table.name + ".csv";
    write_csv(folder / file_name, table);
    TableRecord t;
    t.name = table.name;
    t.title = table.title;
    t.file = output.name + "/" + file_name;
    t.rows = table.rows();
    for (const Column& c : table.columns) t.columns.push_back({c.name, c.unit, c.text});
    record.tables.push_back(std::move(t));
  }
  std::set<std::string> file_names;
  for (const OutputFile& file : output.files) {
    check_component(file.file_name, "file name");
    if (!file_names.insert(file.file_name).second || file.file_name.ends_with(".csv"))
      throw std::invalid_argument(fmt::format("analysis '{}': file name '{}' repeats or clashes",
                                              output.name, file.file_name));
    if (!file.write)
      throw std::logic_error(
          fmt::format("analysis '{}': file '{}' has no writer", output.name, file.file_name));
    file.write(folder / file.file_name);
    record.files.push_back({output.name + "/" + file.file_name, file.description});
  }
  analyses_.push_back(std::move(record));
}

void ResultsWriter::add_report(std::string_view html) {
  if (committed_) throw std::logic_error("ResultsWriter::add_report after commit");
  write_file(staging_ / kReportName, html);
  has_report_ = true;
}

std::string ResultsWriter::manifest_text(bool all_ok) const {
  using nlohmann::json;
  json manifest;
  manifest["manifest_version"] = kManifestVersion;
  manifest["geardyn_version"] = kVersion;
  manifest["status"] = all_ok ? "ok" : "failed";
  json model;
  if (info_.model_path.empty()) {
    model["path"] = nullptr;
    model["sha256"] = nullptr;
  } else {
    std::error_code ec;
    const fs::path absolute = fs::absolute(info_.model_path, ec);
    model["path"] = info_.model_path.string();
    model["absolute_path"] = ec ? info_.model_path.string() : absolute.lexically_normal().string();
    model["sha256"] = info_.model_sha256;
  }
  manifest["model"] = model;
  manifest["start_time"] = format_utc_iso8601(info_.start_time);
  manifest["finish_time"] = format_utc_iso8601(std::chrono::system_clock::now());
  manifest["command_line"] = info_.command_line;
  manifest["report"] = has_report_ ? json(kReportName) : json(nullptr);
  json analyses = json::array();
  for (const auto& a : analyses_) {
    json entry;
    entry["name"] = a.name;
    entry["type"] = a.type;
    entry["status"] = a.status;
    entry["message"] = a.message;
    entry["run_time_s"] = a.run_time_s;  // NaN is written as null
    entry["notes"] = a.notes;
    json tables = json::array();
    for (const auto& t : a.tables) {
      json columns = json::array();
      for (const auto& c : t.columns)
        columns.push_back(
            {{"name", c.name}, {"unit", c.unit}, {"kind", c.text ? "text" : "number"}});
      tables.push_back({{"name", t.name},
                        {"title", t.title},
                        {"file", t.file},
                        {"rows", t.rows},
                        {"columns", std::move(columns)}});
    }
    entry["tables"] = std::move(tables);
    json files = json::array();
    for (const auto& f : a.files)
      files.push_back({{"file", f.file}, {"description", f.description}});
    entry["files"] = std::move(files);
    analyses.push_back(std::move(entry));
  }
  manifest["analyses"] = std::move(analyses);
  // Paths and messages may hold bytes that are not UTF-8; replace them rather than fail the run.
  return manifest.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

void ResultsWriter::commit() {
  if (committed_) throw std::logic_error("ResultsWriter::commit called twice");
  bool all_ok = true;
  for (const auto& a : analyses_) all_ok = all_ok && a.status == to_string(Status::Ok);
  // The manifest is written last: a staging folder without it is an unfinished write.
  write_file(staging_ / kManifestName, manifest_text(all_ok));
  try {
    move_into_place();
  } catch (...) {
    // The staging folder is complete now: keep it, the error message says where it is.
    if (!committed_) keep_staging_ = true;
    throw;
  }
}

void ResultsWriter::move_into_place() {
  std::error_code ec;
  const bool exists = fs::exists(fs::symlink_status(outdir_, ec));
  if (!exists) {
    if (std::rename(staging_.c_str(), outdir_.c_str()) != 0)
      throw std::runtime_error(
          fmt::format("cannot move '{}' to '{}': {}; the new results stay in '{}'",
                      staging_.string(), outdir_.string(), errno_text(errno), staging_.string()));
    committed_ = true;
    return;
  }
  if (!is_replaceable_results_dir(outdir_))
    throw std::runtime_error(fmt::format(
        "results folder '{}' is no longer a geardyn results folder; refusing to replace it; the "
        "new results are in '{}'",
        outdir_.string(), staging_.string()));

  // Preferred: swap both folders in one atomic step; the old results then sit at staging_.
  fs::path old_dir;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, outdir_.c_str(), RENAME_EXCHANGE) == 0) {
    old_dir = staging_;
  } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) {
    // The file system cannot exchange: rename the old away, the new in, restore on failure.
    old_dir = sibling(outdir_, fmt::format(".old-{}", ::getpid()));
    fs::remove_all(old_dir, ec);
    if (std::rename(outdir_.c_str(), old_dir.c_str()) != 0)
      throw std::runtime_error(fmt::format(
          "cannot move the previous results '{}' to '{}': {}; the new results stay in '{}'",
          outdir_.string(), old_dir.string(), errno_text(errno), staging_.string()));
    if (std::rename(staging_.c_str(), outdir_.c_str()) != 0) {
      const int error = errno;
      std::rename(old_dir.c_str(), outdir_.c_str());
      throw std::runtime_error(fmt::format(
          "cannot move '{}' to '{}': {}; the previous results are back in place and the new "
          "results stay in '{}'",
          staging_.string(), outdir_.string(), errno_text(error), staging_.string()));
    }
  } else {
    throw std::runtime_error(
        fmt::format("cannot replace '{}' by '{}': {}; the new results stay in '{}'",
                    outdir_.string(), staging_.string(), errno_text(errno), staging_.string()));
  }
  committed_ = true;  // the new results are in place; what follows only tidies up
  fs::remove_all(old_dir, ec);
  if (ec)
    throw std::runtime_error(fmt::format(
        "the results are in '{}', but the previous results moved to '{}' could not be removed: {}",
        outdir_.string(), old_dir.string(), ec.message()));
}

void write_results(const fs::path& outdir, const RunInfo& info,
                   const std::vector<AnalysisOutput>& outputs, std::string_view report_html) {
  ResultsWriter writer(outdir, info);
  for (const auto& output : outputs) writer.add(output);
  if (!report_html.empty()) writer.add_report(report_html);
  writer.commit();
}

}  // namespace geardyn::io
