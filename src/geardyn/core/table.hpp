#pragma once
// Plain result data shared by every analysis, the CSV/manifest writer and the HTML report:
// named tables whose column names carry their unit, and neutral plot descriptions.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"

namespace geardyn {

/// One column: numeric (`numbers`) or text (`texts`). `name` carries the unit as a suffix
/// (`frequency_hz`, `amplitude_m`, `phase_deg`); `unit` repeats it for the manifest ("Hz").
struct Column {
  std::string name;
  std::string unit;
  std::vector<double> numbers;
  std::vector<std::string> texts;
  bool text = false;

  std::size_t size() const { return text ? texts.size() : numbers.size(); }
};

/// A table: written as `<name>.csv`; `title` is the caption in the report.
struct Table {
  std::string name;
  std::string title;
  std::vector<Column> columns;

  Column& add(std::string column_name, std::string unit, std::vector<double> values = {});
  Column& add_text(std::string column_name, std::vector<std::string> values = {});
  /// Number of rows; all columns must have the same length (checked by `validate`).
  std::size_t rows() const;
  /// Throws std::logic_error if columns differ in length or names repeat.
  void validate() const;
  /// Column by name; throws std::out_of_range naming the table and the column.
  const Column& column(const std::string& column_name) const;
  Column& column(const std::string& column_name);
  bool has_column(const std::string& column_name) const;
};

/// One curve of a plot, or a heat map when `z` is given.
struct Trace {
  /// Bars: a bar chart (e.g. 1/3-octave band levels), one bar per (x[i], y[i]).
  enum class Mode { Lines, Markers, LinesMarkers, Bars };
  std::string name;
  std::vector<double> x, y;
  Mode mode = Mode::Lines;
  std::string dash;                ///< "" solid, "dash", "dot"
  std::vector<std::string> hover;  ///< optional per-point hover text
  /// A heat map (a value over a grid, e.g. the line load over face width x roll angle): z[i][k]
  /// is the value at (x[k], y[i]); x and y are the grid's increasing coordinates (z has y.size()
  /// rows of x.size() values); NaN cells are left blank. Empty: a curve through (x[i], y[i]).
  std::vector<std::vector<double>> z;
  std::string z_label;  ///< heat map: the colour bar's title with unit, e.g. "line load [N/mm]"
  bool is_heatmap() const { return !z.empty(); }
};

/// A 2D plot, rendered by the report with plotly.js.
struct Plot {
  std::string name;  ///< id, unique within an analysis
  std::string title;
  std::string x_label;  ///< with unit, e.g. "speed [rpm]"
  std::string y_label;
  bool x_log = false;
  bool y_log = false;
  bool equal_aspect = false;  ///< orbits
  std::vector<Trace> traces;
};

/// A result file other than a table (mode shapes for ParaView, a reduced component, ...). The
/// analysis computes the data; the results writer calls `write` with the path inside the
/// staging folder, so the file appears only when the whole run is committed.
struct OutputFile {
  std::string file_name;    ///< relative to the analysis folder, e.g. "modes.vtu"
  std::string description;  ///< one line for the manifest and the report
  std::function<void(const std::filesystem::path&)> write;
};

/// What one analysis hands to the writers: tables, plots, status and a trust statement.
struct AnalysisOutput {
  std::string name;  ///< the analysis name from the model (folder name)
  std::string type;  ///< "modal", "campbell", ...
  Status status = Status::Ok;
  std::string message;  ///< empty when ok; otherwise what failed and what usually helps
  double run_time_s = 0.0;
  std::vector<std::string> notes;  ///< how far to trust the result (accuracy, checks done)
  std::vector<Table> tables;
  std::vector<Plot> plots;
  std::vector<OutputFile> files;
};

}  // namespace geardyn
