#pragma once
// The HTML report of a run: one self-contained file (plotly.js and all data inline, no network)
// with a header (model, SHA-256, version, start time, overall status), a table of contents, and
// one section per analysis: status badge, the failure message in full when it failed, the notes
// that say how far to trust the result, interactive plots and the tables.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/run_info.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/core/text.hpp"  // escape_html

namespace geardyn::report {

struct ReportOptions {
  /// Rows of each table shown in the page; longer tables say so and point to their CSV file,
  /// which holds every row.
  std::size_t max_table_rows = 200;
  /// Points of one trace drawn; a longer trace is thinned for display (min/max per bucket when
  /// x increases, every k-th point otherwise) and its plot says so. The CSV keeps every point.
  /// 0 draws every point.
  std::size_t max_points_per_trace = 20000;
  /// Significant digits of the numbers shown in tables (1..17); plot data carry two more.
  int display_digits = 6;
};

/// The complete report page. CSV links are relative (`<analysis>/<table>.csv`), i.e. they work
/// when the page is saved as OUTDIR/report.html next to the tables (io::write_results).
/// Throws std::logic_error if a table is inconsistent (Table::validate), std::invalid_argument
/// if `options.display_digits` is outside 1..17.
std::string render_html(const RunInfo& info, const std::vector<AnalysisOutput>& outputs,
                        const ReportOptions& options = {});

/// JavaScript made safe to place inside a <script> element: every "</script" (any letter case)
/// becomes "<\/script"; everything else is copied unchanged.
std::string escape_script_text(std::string_view js);

}  // namespace geardyn::report
