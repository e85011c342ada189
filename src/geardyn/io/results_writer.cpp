#include "geardyn/io/results_writer.hpp"

#include <fcntl.h>  // open flags of the lock file
#include <fmt/format.h>
#include <signal.h>    // kill(pid, 0): is the process that made a staging folder alive?
#include <sys/file.h>  // flock: one writer per results folder
#include <unistd.h>

#include <algorithm>
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

// Removes the staging folders `OUTDIR.tmp-<pid>` that runs of earlier geardyn versions (which
// staged a whole run next to OUTDIR) left behind when killed before their commit: those of
// processes that no longer exist (a live one may be another run writing). Best effort: what cannot
// be removed stays, and the run goes on.
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

// Writes `file` so that a reader (or a kill) sees the old contents or the new, never a part:
// a temporary sibling renamed over it.
void write_file_atomically(const fs::path& file, std::string_view contents) {
  const fs::path temporary =
      file.parent_path() / fmt::format(".{}.tmp-{}", file.filename().string(), ::getpid());
  write_file(temporary, contents);
  if (std::rename(temporary.c_str(), file.c_str()) != 0) {
    const int error = errno;
    std::error_code ec;
    fs::remove(temporary, ec);
    throw std::runtime_error(
        fmt::format("cannot replace '{}': {}", file.string(), errno_text(error)));
  }
}

// A hidden entry `.<name>.tmp-<digits>` inside a results folder: an analysis folder or file
// being written when its run was killed (the lock guarantees that run is gone).
bool is_unfinished_entry(const std::string& name) {
  const auto at = name.rfind(".tmp-");
  if (name.empty() || name.front() != '.' || at == std::string::npos || at == 0) return false;
  const std::string digits = name.substr(at + 5);
  return !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
}

// What the manifest of an earlier results folder says geardyn wrote there.
std::vector<std::string> entries_written_by_geardyn(const fs::path& dir) {
  std::vector<std::string> entries;
  std::ifstream in(dir / kManifestName);
  if (!in) return entries;
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!manifest.is_object()) return entries;
  entries = {kManifestName, kReportName};
  if (manifest.contains("analyses") && manifest["analyses"].is_array())
    for (const auto& a : manifest["analyses"])
      if (a.is_object() && a.contains("name") && a["name"].is_string())
        entries.push_back(a["name"].get<std::string>());
  return entries;
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

void check_analysis_name(const std::string& name) {
  check_component(name, "analysis name");
  if (name == kManifestName || name == kReportName)
    throw std::invalid_argument(
        fmt::format("analysis name '{}' is reserved in the results folder", name));
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
  if (!is_replaceable_results_dir(outdir_))
    throw std::runtime_error(fmt::format(
        "results folder '{}' exists and is not a geardyn results folder (not a folder, or not "
        "empty and without a geardyn manifest.json); refusing to replace it: choose another "
        "output folder or remove it",
        outdir_.string()));
  if (info_.model_sha256.empty() && !info_.model_path.empty())
    info_.model_sha256 = sha256_file(info_.model_path);
  lock_outdir();
  remove_stale_staging(outdir_);
  old_entries_ = entries_written_by_geardyn(outdir_);
}

// The earlier run's entries go, anything else stays — unless a new analysis would have to
// overwrite it. `remove` gets what is ours, `keep` the rest; throws on a clash.
static void sort_entries(const fs::path& outdir, const std::vector<std::string>& old_entries,
                         const std::vector<std::string>& planned, std::vector<fs::path>* remove,
                         std::vector<std::string>* keep) {
  std::error_code ec;
  if (!fs::is_directory(outdir, ec)) return;
  if (!is_replaceable_results_dir(outdir))
    throw std::runtime_error(fmt::format(
        "results folder '{}' is no longer a geardyn results folder; refusing to replace it",
        outdir.string()));
  for (const auto& entry : fs::directory_iterator(outdir)) {
    const std::string name = entry.path().filename().string();
    if (std::find(old_entries.begin(), old_entries.end(), name) != old_entries.end() ||
        is_unfinished_entry(name)) {
      if (remove) remove->push_back(entry.path());
      continue;
    }
    if (std::find(planned.begin(), planned.end(), name) != planned.end())
      throw std::runtime_error(fmt::format(
          "results folder '{}' holds '{}', which geardyn did not write, and analysis '{}' "
          "would overwrite it: move it away or choose another output folder",
          outdir.string(), name, name));
    if (keep) keep->push_back(name);
  }
}

void ResultsWriter::check(const std::vector<std::string>& planned) const {
  for (std::size_t i = 0; i < planned.size(); ++i) {
    check_analysis_name(planned[i]);
    for (std::size_t j = 0; j < i; ++j)
      if (planned[j] == planned[i])
        throw std::invalid_argument(fmt::format("analysis name '{}' repeats", planned[i]));
  }
  sort_entries(outdir_, old_entries_, planned, nullptr, nullptr);
}

void ResultsWriter::begin(const std::vector<std::string>& planned) {
  if (begun_) throw std::logic_error("ResultsWriter::begin called twice");
  check(planned);
  std::vector<fs::path> to_remove;
  sort_entries(outdir_, old_entries_, planned, &to_remove, &kept_);
  std::error_code ec;
  std::sort(kept_.begin(), kept_.end());
  for (const auto& path : to_remove) {
    fs::remove_all(path, ec);
    if (ec)
      throw std::runtime_error(
          fmt::format("cannot remove the earlier result '{}': {}", path.string(), ec.message()));
  }
  fs::create_directories(outdir_, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot create the results folder '{}': {}", outdir_.string(), ec.message()));
  planned_ = planned;
  begun_ = true;
  write_manifest(Phase::InProgress);
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
  if (begun_ && !committed_) {
    try {
      write_manifest(Phase::Stopped);  // best effort: a destructor must not throw
    } catch (...) {
    }
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void ResultsWriter::add(const AnalysisOutput& output) {
  if (committed_) throw std::logic_error("ResultsWriter::add after commit");
  check_analysis_name(output.name);
  for (const auto& a : analyses_)
    if (a.name == output.name)
      throw std::invalid_argument(fmt::format("analysis name '{}' repeats", output.name));
  if (!begun_) begin({output.name});
  if (std::find(kept_.begin(), kept_.end(), output.name) != kept_.end())
    throw std::runtime_error(fmt::format(
        "results folder '{}' holds '{}', which geardyn did not write; refusing to overwrite it",
        outdir_.string(), output.name));

  // Written aside, then renamed into place: a kill leaves a hidden folder, never a half one.
  const fs::path folder = outdir_ / fmt::format(".{}.tmp-{}", output.name, ::getpid());
  const fs::path final_folder = outdir_ / output.name;
  std::error_code ec;
  fs::remove_all(folder, ec);
  fs::create_directory(folder, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot create the folder '{}': {}", folder.string(), ec.message()));
  AnalysisRecord record;
  try {
    record = write_analysis(output, folder);
    if (std::rename(folder.c_str(), final_folder.c_str()) != 0)
      throw std::runtime_error(fmt::format("cannot move '{}' to '{}': {}", folder.string(),
                                           final_folder.string(), errno_text(errno)));
  } catch (...) {
    fs::remove_all(folder, ec);
    throw;
  }
  analyses_.push_back(std::move(record));
  planned_.erase(std::remove(planned_.begin(), planned_.end(), output.name), planned_.end());
  write_manifest(Phase::InProgress);
}

ResultsWriter::AnalysisRecord ResultsWriter::write_analysis(const AnalysisOutput& output,
                                                            const fs::path& folder) {
  AnalysisRecord record;
  record.name = output.name;
  record.type = output.type;
  record.status = std::string(to_string(output.status));
  record.message = output.message;
  record.run_time_s = output.run_time_s;
  record.notes = output.notes;

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
  return record;
}

void ResultsWriter::add_report(std::string_view html) {
  if (committed_) throw std::logic_error("ResultsWriter::add_report after commit");
  if (!begun_) begin({});
  write_file_atomically(outdir_ / kReportName, html);
  if (!has_report_) {
    has_report_ = true;
    write_manifest(Phase::InProgress);
  }
}

void ResultsWriter::write_manifest(Phase phase) const {
  write_file_atomically(outdir_ / kManifestName, manifest_text(phase));
}

std::string ResultsWriter::manifest_text(Phase phase) const {
  using nlohmann::json;
  bool all_ok = true;
  for (const auto& a : analyses_) all_ok = all_ok && a.status == to_string(Status::Ok);
  json manifest;
  manifest["manifest_version"] = kManifestVersion;
  manifest["geardyn_version"] = kVersion;
  manifest["status"] = phase != Phase::Complete ? "incomplete" : all_ok ? "ok" : "failed";
  manifest["complete"] = phase == Phase::Complete;
  if (phase == Phase::InProgress)
    manifest["run_message"] =
        "written while the run was in progress: the analyses listed are complete; those under "
        "not_run had not finished (if geardyn is no longer running, it was stopped before them)";
  else if (phase == Phase::Stopped)
    manifest["run_message"] =
        "the run ended with an error before it finished: the analyses listed are complete; "
        "those under not_run were not run";
  manifest["not_run"] = planned_;
  manifest["kept_files"] = kept_;
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
  if (!begun_) begin({});
  write_manifest(Phase::Complete);
  committed_ = true;
}

void write_results(const fs::path& outdir, const RunInfo& info,
                   const std::vector<AnalysisOutput>& outputs, std::string_view report_html) {
  ResultsWriter writer(outdir, info);
  std::vector<std::string> names;
  for (const auto& output : outputs) names.push_back(output.name);
  writer.begin(names);
  for (const auto& output : outputs) writer.add(output);
  if (!report_html.empty()) writer.add_report(report_html);
  writer.commit();
}

}  // namespace geardyn::io
