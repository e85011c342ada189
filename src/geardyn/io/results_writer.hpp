#pragma once
// The results folder of a run:
//
//   OUTDIR/manifest.json            what ran, on which model (SHA-256), status of each analysis
//   OUTDIR/report.html              the self-contained report (when given)
//   OUTDIR/<analysis>/<table>.csv   every table of every analysis
//
// Everything is written into a staging folder next to OUTDIR (`OUTDIR.tmp-<pid>`, same file
// system) and moved into place by one rename at commit, so OUTDIR is either the previous complete
// results or the new complete results, never a half-written mix. A process killed before the
// commit leaves only the staging folder, which has no manifest.json.
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
  /// Prepares the staging folder `OUTDIR.tmp-<pid>` (creating OUTDIR's parent folders if needed,
  /// removing a leftover staging folder of the same name, and the staging folders of earlier
  /// runs into OUTDIR whose process no longer exists). Throws std::runtime_error when another
  /// writer (another geardyn run) holds OUTDIR. Throws std::runtime_error naming the
  /// path when OUTDIR exists but cannot be replaced safely: it is not a folder, or it is a
  /// non-empty folder without a geardyn manifest.json (so that `-o ~` never deletes a home).
  ResultsWriter(std::filesystem::path outdir, RunInfo info);
  /// Removes the staging folder unless commit() succeeded. Never throws.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Writes the tables of `output` to `<analysis>/<table>.csv` in the staging folder and records
  /// the analysis (also a failed one, with its status and message) for the manifest.
  /// Throws std::invalid_argument when the analysis name is not a usable folder name or repeats,
  /// or a table name repeats within the analysis; std::logic_error for an inconsistent table;
  /// std::runtime_error naming the path on I/O failure.
  void add(const AnalysisOutput& output);

  /// Writes `html` as report.html and lists it in the manifest.
  void add_report(std::string_view html);

  /// Writes manifest.json and moves the staging folder to OUTDIR. An existing OUTDIR is swapped
  /// out atomically (renameat2 RENAME_EXCHANGE; on file systems without it: renamed away, the new
  /// folder renamed in, the old one restored if that fails) and then deleted.
  /// Throws std::runtime_error naming the paths on failure; OUTDIR is then left as it was and
  /// the complete new results stay in the staging folder (not removed by the destructor).
  /// One ResultsWriter per OUTDIR at a time in a process (the staging name holds only the pid).
  void commit();

  const std::filesystem::path& outdir() const { return outdir_; }
  const std::filesystem::path& staging_dir() const { return staging_; }
  bool committed() const { return committed_; }

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

  std::string manifest_text(bool all_ok) const;
  void move_into_place();

  std::filesystem::path outdir_;
  std::filesystem::path staging_;
  RunInfo info_;
  std::vector<AnalysisRecord> analyses_;
  bool has_report_ = false;
  bool committed_ = false;     // the new results are at outdir_
  bool keep_staging_ = false;  // commit failed after the staging folder was complete
};

/// Writes a whole run at once: every output (failed ones included), `report_html` as report.html
/// unless it is empty, the manifest, then commits. Same errors as ResultsWriter.
void write_results(const std::filesystem::path& outdir, const RunInfo& info,
                   const std::vector<AnalysisOutput>& outputs, std::string_view report_html);

/// True when `dir` may be replaced by a results folder: it does not exist, is an empty folder, or
/// is a folder whose manifest.json was written by geardyn.
bool is_replaceable_results_dir(const std::filesystem::path& dir);

}  // namespace geardyn::io
