#pragma once
// The results folder of a run:
//
//   OUTDIR/manifest.json            what ran, on which model (SHA-256), status of each analysis
//   OUTDIR/report.html              the self-contained report (when given)
//   OUTDIR/<analysis>/<table>.csv   every table of every analysis
//
// Results are kept as they are made: each analysis is written when it finishes (into a hidden
// folder `OUTDIR/.<analysis>.tmp-<pid>`, renamed into place in one step) and the manifest is
// rewritten (atomically) after it. Until the run ends the manifest says "status": "incomplete",
// "complete": false and lists under "not_run" the analyses still to come, so a run killed in
// its last analysis keeps every analysis before it, in a folder that says it is incomplete.
//
// An earlier geardyn results folder is replaced when the run begins (begin()): what its
// manifest lists (analysis folders, manifest.json, report.html) is removed; anything else in it
// (a user's post-processing script) is kept, listed in the manifest under "kept_files" and
// reported by kept_files(). A folder that is neither empty nor a geardyn results folder is
// never touched.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/run_info.hpp"
#include "geardyn/core/table.hpp"

namespace geardyn::io {

using geardyn::RunInfo;

/// Version of the manifest layout; raised when a field changes meaning or is removed.
inline constexpr int kManifestVersion = 1;

class ResultsWriter {
 public:
  /// Checks OUTDIR and locks it; changes nothing on disk yet (except creating OUTDIR's parent
  /// folders and the lock file `.OUTDIR.lock` next to it, and removing the staging folders
  /// `OUTDIR.tmp-<pid>` that runs of earlier geardyn versions killed before their commit left).
  /// Throws std::runtime_error when another writer (another geardyn run) holds OUTDIR, or naming
  /// the path when OUTDIR exists but may not be replaced: it is not a folder, or it is a
  /// non-empty folder without a geardyn manifest.json (so that `-o ~` never deletes a home).
  ResultsWriter(std::filesystem::path outdir, RunInfo info);
  /// Marks an unfinished run's manifest as stopped ("complete": false) when begun but not
  /// committed, and releases the lock. Never throws.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// The checks of begin(planned), without changing anything: call it before computing.
  void check(const std::vector<std::string>& planned) const;

  /// Starts writing: `planned` are the names of the analyses that will be added (in order).
  /// Throws std::invalid_argument when a name is not a usable folder name or repeats, and
  /// std::runtime_error when OUTDIR holds an entry of that name that geardyn did not write —
  /// both before anything is removed. Then removes the earlier run's results (keeping foreign
  /// files), creates OUTDIR and writes the "incomplete" manifest.
  void begin(const std::vector<std::string>& planned);

  /// Writes the tables and files of `output` to `<analysis>/` and records the analysis (also a
  /// failed one, with its status and message) in the manifest, rewritten at once. Calls
  /// begin({output.name}) first when the run was not begun. Throws std::invalid_argument when
  /// the analysis name is not a usable folder name or repeats, or a table name repeats within
  /// the analysis; std::logic_error for an inconsistent table; std::runtime_error naming the
  /// path on I/O failure (the analysis is then not listed as written).
  void add(const AnalysisOutput& output);

  /// Writes `html` as report.html (replaced in one step) and lists it in the manifest.
  void add_report(std::string_view html);

  /// Writes the final manifest: "complete": true, "status" ok or failed.
  void commit();

  const std::filesystem::path& outdir() const { return outdir_; }
  bool committed() const { return committed_; }
  /// Entries of an earlier results folder that geardyn did not write, kept in place.
  const std::vector<std::string>& kept_files() const { return kept_; }

 private:
  /// Holds `.OUTDIR.lock` (a hidden file next to OUTDIR) locked while this writer lives, so a
  /// second run into the same folder is refused instead of silently replacing the first.
  void lock_outdir();
  int lock_fd_ = -1;
  struct ColumnRecord {
    std::string name, unit;
    bool text = false;
  };
  struct TableRecord {
    std::string name, title, file;
    std::size_t rows = 0;
    std::vector<ColumnRecord> columns;
  };
  struct FileRecord {
    std::string file, description;
  };
  struct AnalysisRecord {
    std::string name, type, status, message;
    double run_time_s = 0.0;
    std::vector<std::string> notes;
    std::vector<TableRecord> tables;
    std::vector<FileRecord> files;
  };

  enum class Phase { Complete, InProgress, Stopped };
  std::string manifest_text(Phase phase) const;
  void write_manifest(Phase phase) const;
  AnalysisRecord write_analysis(const AnalysisOutput& output, const std::filesystem::path& folder);

  std::filesystem::path outdir_;
  RunInfo info_;
  std::vector<std::string> old_entries_;  // what the earlier run's manifest lists
  std::vector<std::string> planned_;
  std::vector<std::string> kept_;
  std::vector<AnalysisRecord> analyses_;
  bool begun_ = false;
  bool has_report_ = false;
  bool committed_ = false;
};

/// Writes a whole run at once: every output (failed ones included), `report_html` as report.html
/// unless it is empty, then commits. Same errors as ResultsWriter.
void write_results(const std::filesystem::path& outdir, const RunInfo& info,
                   const std::vector<AnalysisOutput>& outputs, std::string_view report_html);

/// True when `dir` may be replaced by a results folder: it does not exist, is an empty folder, or
/// is a folder whose manifest.json was written by geardyn (complete or not).
bool is_replaceable_results_dir(const std::filesystem::path& dir);

}  // namespace geardyn::io
